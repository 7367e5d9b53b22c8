// Stage 4, after cutting: the cut points a polygon made inside its own
// faces, or off every tracked face, are collapsed away where the tets allow
// it. Near-parallel triangles stacked within a fraction of the target
// length (overlapping parts of a CAD soup) cut the same thin tets again and
// again: each plane crosses the slivers its neighbours left, so the points
// per triangle grew with the number inserted before it
// (manifold/openscad-nonmanifold-crash: 60 for the first hundred triangles,
// 7,000 for some of the last, 1.2 million tets from 759 triangles). A point
// interior to one polygon's patch of tracked faces carries nothing the
// surface needs: collapsed onto a neighbour in that patch, the patch covers
// the same region of the same plane, with the same marks, whenever every tet
// around it stays positive (exact). Points on the polygon's edges, or where
// it crosses another tracked face, stay; so do points whose collapse would
// make a tet worse (AMIPS) than the worst around them: collapsed regardless,
// the patches became fans of needles improvement could not mend
// (trimesh/mode5's max AMIPS 518 -> 42,000).

#include "triangle_inserter.h"
#include "vertex_collapse.h"

#include <mr/check/tet_check.h>
#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mr::tetmesh::detail {

std::size_t TriangleInserter::settle_cut_points() {
  std::vector<Index> points(new_vertices_.begin(), new_vertices_.end());
  std::sort(points.begin(), points.end());
  std::size_t settled = 0;
  for (const Index v : points) settled += mesh_.vertex_alive(v) && collapse_cut_point(v) ? 1 : 0;
  counters_.settled_points += settled;
  return settled;
}

// The neighbours v may collapse onto, nearest first: every neighbour when v
// is on no tracked face; the corners of its faces when those make one disk
// around v with the same marks; none otherwise.
std::vector<Index> TriangleInserter::settling_targets(Index v, std::span<const Index> star) const {
  std::map<std::array<Index, 3>, std::vector<std::uint32_t>> faces;  // sorted corners -> marks
  std::vector<Index> neighbours;
  for (const Index t : star) {
    const Tet& c = mesh_.tet(t);
    for (int k = 0; k < 4; ++k) {
      if (c[k] != v) neighbours.push_back(c[k]);
      if (c[k] == v || !mesh_.is_surface_face(t, k)) continue;
      std::array<Index, 3> f = mesh_.face_vertices(t, k);
      std::sort(f.begin(), f.end());
      const auto ids = mesh_.surface_ids(t, k);
      faces.try_emplace(f, ids.begin(), ids.end());
    }
  }
  std::map<Index, int> fan_edges;  // the other end of each tracked edge at v -> faces on it
  for (const auto& [f, ids] : faces) {
    if (ids != faces.begin()->second) return {};
    for (const Index w : f)
      if (w != v) ++fan_edges[w];
  }
  if (!faces.empty()) {
    neighbours.clear();
    for (const auto& [w, count] : fan_edges) {
      if (count != 2) return {};  // v is on the patch's edge
      neighbours.push_back(w);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  const Vec3d& p = mesh_.position(v).approx;
  std::stable_sort(neighbours.begin(), neighbours.end(), [&](Index a, Index b) {
    return (mesh_.position(a).approx - p).squaredNorm() < (mesh_.position(b).approx - p).squaredNorm();
  });
  return neighbours;
}

namespace {

// AMIPS on the doubles; infinite for a tet flat or inverted (exactly).
double energy(const Mesh& mesh, const Tet& c) {
  const double e = check::amips_energy(mesh.position(c[0]).approx, mesh.position(c[1]).approx,
                                       mesh.position(c[2]).approx, mesh.position(c[3]).approx);
  return std::isfinite(e) && e > 0 ? e : std::numeric_limits<double>::infinity();
}

double largest_energy(const Mesh& mesh, std::span<const Index> tets) {
  double largest = 0.0;
  for (const Index t : tets) largest = std::max(largest, energy(mesh, mesh.tet(t)));
  return largest;
}

// The largest AMIPS energy of the tets collapsing onto u would make.
double largest_energy_after(const Mesh& mesh, Index u, const StarBoundary& boundary) {
  std::vector<ConeTet> tets;
  cone(u, boundary.faces, tets);
  double largest = 0.0;
  for (const ConeTet& tet : tets) largest = std::max(largest, energy(mesh, tet.corners));
  return largest;
}

}  // namespace

bool TriangleInserter::collapse_cut_point(Index v) {
  const Index seed = seed_tet_[v];
  if (seed == kNoTet || !mesh_.tet_alive(seed) || mesh_.corner_of(seed, v) < 0) return false;
  const std::vector<Index> star = tets_around_vertex(mesh_, v, seed);
  const std::vector<Index> targets = settling_targets(v, star);
  if (targets.empty()) return false;
  const StarBoundary boundary = star_boundary(mesh_, std::span<const Index>(&v, 1), star);
  const double before = largest_energy(mesh_, star);
  std::vector<Index> created;
  for (const Index u : targets) {
    if (!(largest_energy_after(mesh_, u, boundary) <= before)) continue;
    if (!collapse_vertices(mesh_, std::span<const Index>(&v, 1), u, star, boundary, &created)) continue;
    for (const Index t : boundary.outside)
      for (const Index w : mesh_.tet(t)) seed_tet_[w] = t;
    for (const Index t : created)
      for (const Index w : mesh_.tet(t)) seed_tet_[w] = t;
    return true;
  }
  return false;
}

}  // namespace mr::tetmesh::detail
