#include <mr/tetmesh/incidence.h>

#include <mr/core/errors.h>

#include <algorithm>
#include <string>
#include <unordered_set>

namespace mr::tetmesh {

VertexTets::VertexTets(const Mesh& mesh) : offsets_(mesh.vertex_slots() + 1, 0) {
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (const Index v : mesh.tet(t)) ++offsets_[v + 1];
  }
  for (std::size_t v = 0; v + 1 < offsets_.size(); ++v) offsets_[v + 1] += offsets_[v];
  tets_.resize(offsets_.back());
  std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (const Index v : mesh.tet(t)) tets_[fill[v]++] = t;
  }
}

namespace {

// Walks the tets around vertex v from `seed` (breadth first over faces that
// contain v) until `stop` returns true for a tet; returns the tets visited.
template <class Stop>
std::vector<Index> walk_star(const Mesh& mesh, Index v, Index seed, Stop stop) {
  // Most stars have a few dozen tets, where a linear search of the star is
  // fastest; cut points on lines where many triangles cross have thousands,
  // where it was quadratic, so a hash set takes over past a size.
  constexpr std::size_t kLinearSearchLimit = 64;
  std::vector<Index> star;
  star.reserve(kLinearSearchLimit);
  star.push_back(seed);
  std::unordered_set<Index> seen;
  auto is_new = [&](Index u) {
    if (star.size() < kLinearSearchLimit) return std::find(star.begin(), star.end(), u) == star.end();
    if (seen.empty()) seen.insert(star.begin(), star.end());
    return seen.insert(u).second;
  };
  for (std::size_t i = 0; i < star.size(); ++i) {
    const Index t = star[i];
    if (stop(t)) break;
    const int opposite = mesh.corner_of(t, v);
    for (int f = 0; f < 4; ++f) {
      const Index u = mesh.neighbour(t, f);
      // Faces other than the one opposite v contain v: their neighbour is in the star.
      if (f == opposite || u == kNoTet) continue;
      if (is_new(u)) star.push_back(u);
    }
  }
  return star;
}

void require_corner(const Mesh& mesh, Index v, Index seed, const char* caller) {
  if (!mesh.tet_alive(seed) || mesh.corner_of(seed, v) < 0) {
    throw UsageError(std::string(caller) + ": seed tet " + std::to_string(seed) +
                     " is not a live tet with vertex " + std::to_string(v));
  }
}

}  // namespace

std::vector<Index> tets_around_vertex(const Mesh& mesh, Index v, Index seed) {
  require_corner(mesh, v, seed, "tets_around_vertex");
  std::vector<Index> star = walk_star(mesh, v, seed, [](Index) { return false; });
  std::sort(star.begin(), star.end());
  return star;
}

Index tet_with_edge(const Mesh& mesh, Index a, Index b, Index seed) {
  require_corner(mesh, a, seed, "tet_with_edge");
  Index found = kNoTet;
  walk_star(mesh, a, seed, [&](Index t) {
    if (mesh.corner_of(t, b) < 0) return false;
    found = t;
    return true;
  });
  return found;
}

std::vector<Index> tets_around_edge(const Mesh& mesh, Index a, Index b, Index seed) {
  if (!mesh.tet_alive(seed) || mesh.corner_of(seed, a) < 0 || mesh.corner_of(seed, b) < 0) {
    throw UsageError("tets_around_edge: seed tet " + std::to_string(seed) + " is not a live tet with edge " +
                     std::to_string(a) + "-" + std::to_string(b));
  }
  // The tets around an edge are a ring (a fan at the box) of a few: a
  // linear search is enough.
  std::vector<Index> ring{seed};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Index t = ring[i];
    for (int f = 0; f < 4; ++f) {
      // Face f, opposite corner f, contains the edge unless that corner is a or b.
      const Index corner = mesh.tet(t)[f];
      const Index u = mesh.neighbour(t, f);
      if (corner == a || corner == b || u == kNoTet) continue;
      if (std::find(ring.begin(), ring.end(), u) == ring.end()) ring.push_back(u);
    }
  }
  std::sort(ring.begin(), ring.end());
  return ring;
}

}  // namespace mr::tetmesh
