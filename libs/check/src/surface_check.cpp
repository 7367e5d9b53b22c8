#include "exact.h"
#include "welded.h"

#include <mr/check/self_intersections.h>
#include <mr/check/surface_check.h>
#include <mr/core/union_find.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace mr::check {
namespace {

bool repeats_index(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; }

struct EdgeUse {
  Index lo, hi;
  bool forward;  // traversed lo -> hi
  std::size_t face;
  int corner_lo, corner_hi;  // local corners of lo and hi in the face
};

std::vector<EdgeUse> edge_uses(const std::vector<Triangle>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    if (repeats_index(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = k, b = (k + 1) % 3;
      const bool forward = t[a] < t[b];
      uses.push_back(
          {std::min(t[a], t[b]), std::max(t[a], t[b]), forward, f, forward ? a : b, forward ? b : a});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  return uses;
}

void count_edges(const detail::Welded& mesh, SurfaceReport& report) {
  const std::vector<EdgeUse> uses = edge_uses(mesh.triangles);
  // Corners (face, local vertex) around a vertex are joined across shared edges;
  // a vertex whose corners fall into several groups has several fans.
  UnionFind corners(3 * mesh.triangles.size());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    const std::size_t count = j - i;
    if (count == 1) ++report.boundary_edges;
    if (count > 2) ++report.nonmanifold_edges;
    if (count == 2 && uses[i].forward == uses[i + 1].forward) ++report.inconsistent_edges;
    for (std::size_t k = i + 1; k < j; ++k) {
      corners.unite(3 * uses[i].face + uses[i].corner_lo, 3 * uses[k].face + uses[k].corner_lo);
      corners.unite(3 * uses[i].face + uses[i].corner_hi, 3 * uses[k].face + uses[k].corner_hi);
    }
    i = j;
  }
  std::vector<std::pair<Index, std::size_t>> vertex_fans;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (repeats_index(mesh.triangles[f])) continue;
    for (int k = 0; k < 3; ++k) vertex_fans.emplace_back(mesh.triangles[f][k], corners.find(3 * f + k));
  }
  std::sort(vertex_fans.begin(), vertex_fans.end());
  vertex_fans.erase(std::unique(vertex_fans.begin(), vertex_fans.end()), vertex_fans.end());
  for (std::size_t i = 0; i < vertex_fans.size();) {
    std::size_t j = i + 1;
    while (j < vertex_fans.size() && vertex_fans[j].first == vertex_fans[i].first) ++j;
    if (j - i > 1) ++report.nonmanifold_vertices;
    i = j;
  }
}

void count_faces(const detail::Welded& mesh, SurfaceReport& report) {
  std::vector<Triangle> sorted;
  UnionFind vertices(mesh.positions.size());
  for (const Triangle& t : mesh.triangles) {
    Triangle s = t;
    std::sort(s.begin(), s.end());
    sorted.push_back(s);
    vertices.unite(t[0], t[1]);
    vertices.unite(t[1], t[2]);
    const Vec3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    if (repeats_index(t) || detail::exactly_collinear(a, b, c)) ++report.degenerate_faces;
  }
  std::sort(sorted.begin(), sorted.end());
  report.duplicate_faces =
      sorted.size() - static_cast<std::size_t>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  std::vector<std::size_t> roots;
  for (const Triangle& t : mesh.triangles) roots.push_back(vertices.find(t[0]));
  std::sort(roots.begin(), roots.end());
  report.components = static_cast<std::size_t>(std::unique(roots.begin(), roots.end()) - roots.begin());
}

// The sum of the absolute values of the six products in a . (b x c).
double triple_product_magnitude(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d x = a.cwiseAbs(), y = b.cwiseAbs(), z = c.cwiseAbs();
  return x.x() * (y.y() * z.z() + y.z() * z.y()) + x.y() * (y.z() * z.x() + y.x() * z.z()) +
         x.z() * (y.x() * z.y() + y.y() * z.x());
}

double signed_volume(const detail::Welded& mesh) {
  if (mesh.triangles.empty()) return 0;
  // The box of the corners only: an unused vertex far away would move the
  // origin off the surface.
  Vec3d lo = mesh.positions[mesh.triangles[0][0]], hi = lo;
  for (const Triangle& t : mesh.triangles)
    for (const Index v : t) {
      lo = lo.cwiseMin(mesh.positions[v]);
      hi = hi.cwiseMax(mesh.positions[v]);
    }
  const Vec3d center = 0.5 * (lo + hi);  // a nearby origin keeps the sum accurate
  double six_volume = 0, magnitude = 0;
  for (const Triangle& t : mesh.triangles) {
    const Vec3d a = mesh.positions[t[0]] - center, b = mesh.positions[t[1]] - center,
                c = mesh.positions[t[2]] - center;
    six_volume += a.dot(b.cross(c));
    magnitude += triple_product_magnitude(a, b, c);
  }
  // Ten roundings per term (the differences, products and sums) and one per
  // addition: a sum within that bound of zero may have the wrong sign (a
  // sliver reaching far away), and the sign says whether the surface faces out.
  const double bound = (10.0 + static_cast<double>(mesh.triangles.size())) * 0x1p-53 * magnitude;
  if (std::abs(six_volume) > bound) return six_volume / 6;
  return detail::exact_six_volume(mesh.positions, mesh.triangles) / 6;
}

}  // namespace

std::string watertight_failures(const SurfaceReport& r) {
  std::string out;
  const auto add = [&](std::size_t count, const char* one, const char* many) {
    if (count == 0) return;
    if (!out.empty()) out += ", ";
    out += std::to_string(count) + " " + (count == 1 ? one : many);
  };
  add(r.boundary_edges, "boundary edge", "boundary edges");
  add(r.nonmanifold_edges, "non-manifold edge", "non-manifold edges");
  add(r.nonmanifold_vertices, "non-manifold vertex", "non-manifold vertices");
  add(r.inconsistent_edges, "inconsistently oriented edge", "inconsistently oriented edges");
  add(r.degenerate_faces, "degenerate face", "degenerate faces");
  if (r.self_intersecting_pairs > 0)
    add(static_cast<std::size_t>(r.self_intersecting_pairs), "self-intersecting face pair",
        "self-intersecting face pairs");
  if (r.self_intersecting_pairs < 0)
    out += std::string(out.empty() ? "" : ", ") + "self-intersections not checked";
  if (out.empty() && !(r.volume > 0))
    out = "not oriented outward (enclosed volume " + std::to_string(r.volume) + ")";
  return out;
}

SurfaceReport check_surface(const TriangleSoup& soup, const SurfaceCheckOptions& options) {
  const detail::Welded welded = detail::weld_identical(soup);
  SurfaceReport report;
  report.vertices = welded.positions.size();
  report.faces = welded.triangles.size();
  count_edges(welded, report);
  count_faces(welded, report);
  report.volume = signed_volume(welded);
  if (options.self_intersections) report.self_intersecting_pairs = count_self_intersections(soup);
  return report;
}

}  // namespace mr::check
