#include <mr/tetmesh/open_surface_winding.h>

#include "regions.h"

#include <mr/core/errors.h>
#include <mr/kernel/predicates.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/tetmesh/winding_filter.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace mr::tetmesh {
namespace {

using Edge = std::array<Index, 2>;

// The boundary as closed loops of vertices (edge i runs from loop[i] to
// loop[i + 1], the last back to the first). A boundary is a cycle: every
// vertex has as many edges in as out, so a walk along unused edges can
// only stop where it started.
std::vector<std::vector<Index>> boundary_loops(const TriangleSoup& surface) {
  const std::vector<Edge> edges = detail::chain_boundary(surface);
  std::vector<char> used(edges.size(), 0);
  const auto unused_from = [&](Index v) -> std::size_t {
    auto it = std::lower_bound(edges.begin(), edges.end(), Edge{v, 0});
    for (; it != edges.end() && (*it)[0] == v; ++it)
      if (used[static_cast<std::size_t>(it - edges.begin())] == 0)
        return static_cast<std::size_t>(it - edges.begin());
    throw UsageError("the boundary of a chain is not a cycle");
  };
  std::vector<std::vector<Index>> loops;
  for (std::size_t first = 0; first < edges.size(); ++first) {
    if (used[first] != 0) continue;
    std::vector<Index> loop{edges[first][0]};
    for (std::size_t e = first;; e = unused_from(loop.back())) {
      used[e] = 1;
      if (edges[e][1] == loop.front()) break;
      loop.push_back(edges[e][1]);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Triangles whose boundary is `loop`: every other vertex is cut off by a
// triangle with its two neighbours, halving the loop, until three are
// left. Each round's triangles have as boundary the loop minus the halved
// one, so all of them have the loop's. Loops follow the surface's edges,
// so most triangles are small (neighbours along the loop) and only a few
// span it: a cone from one point over a long loop made every one of its
// triangles span it, and the winding number of the cap cost as much per
// tet as the surface's.
void cap_loop(std::vector<Index> loop, std::vector<Triangle>& triangles) {
  while (loop.size() >= 3) {
    if (loop.size() == 3) {
      triangles.push_back({loop[0], loop[1], loop[2]});
      return;
    }
    std::vector<Index> halved;
    for (std::size_t i = 0; i < loop.size(); i += 2) {
      halved.push_back(loop[i]);
      if (i + 1 < loop.size()) triangles.push_back({loop[i], loop[i + 1], loop[(i + 2) % loop.size()]});
    }
    loop = std::move(halved);
  }
  // Two vertices left: an edge run along both ways, which bounds nothing.
}

// A surface with the same boundary as `surface`: each boundary loop capped.
TriangleSoup cap(const TriangleSoup& surface) {
  TriangleSoup cap;
  cap.positions = surface.positions;
  for (std::vector<Index>& loop : boundary_loops(surface)) cap_loop(std::move(loop), cap.triangles);
  return cap;
}

// +1 when segment a->b passes through the interior of triangle pqr from its
// front (where (q - p) x (r - p) points) to its back, where the winding
// number is one more; -1 the other way; 0 when it misses the triangle.
// nullopt when it touches it otherwise: an end on it, through an edge or a
// corner, or along its plane.
std::optional<int> crossing(const Vec3d& p, const Vec3d& q, const Vec3d& r, const Vec3d& a, const Vec3d& b) {
  const int side_a = orient3d(p, q, r, a), side_b = orient3d(p, q, r, b);
  if (side_a == 0 && side_b == 0) return std::nullopt;
  if (side_a == side_b) return 0;
  // The line through a and b meets the plane once: inside the triangle
  // when it passes each edge on the same side.
  const int e0 = orient3d(a, b, p, q), e1 = orient3d(a, b, q, r), e2 = orient3d(a, b, r, p);
  const bool one_way = e0 >= 0 && e1 >= 0 && e2 >= 0, other_way = e0 <= 0 && e1 <= 0 && e2 <= 0;
  if (!one_way && !other_way) return 0;
  if (side_a == 0 || side_b == 0 || e0 == 0 || e1 == 0 || e2 == 0) return std::nullopt;
  return side_a > 0 ? 1 : -1;
}

// Signed crossings of segments with the triangles of a soup. Flat
// triangles (corners on a line, exactly) bound nothing and are skipped.
class CrossingCounter {
 public:
  explicit CrossingCounter(const TriangleSoup& soup)
      : soup_(soup), tree_(soup), flat_(soup.triangles.size(), 0) {
    tbb::parallel_for(std::size_t{0}, soup.triangles.size(),
                      [&](std::size_t i) { flat_[i] = collinear(corner(i, 0), corner(i, 1), corner(i, 2)); });
  }

  // nullopt when the segment touches a triangle other than by a crossing.
  std::optional<int> count(const Vec3d& a, const Vec3d& b, std::vector<std::uint32_t>& scratch) const {
    scratch.clear();
    tree_.triangles_in_box(a.cwiseMin(b), a.cwiseMax(b), scratch);
    int total = 0;
    for (const std::uint32_t i : scratch) {
      if (flat_[i] != 0) continue;
      const std::optional<int> c = crossing(corner(i, 0), corner(i, 1), corner(i, 2), a, b);
      if (!c) return std::nullopt;
      total += *c;
    }
    return total;
  }

 private:
  const Vec3d& corner(std::size_t i, int k) const { return soup_.positions[soup_.triangles[i][k]]; }

  const TriangleSoup& soup_;
  spatial::AabbTree tree_;
  std::vector<char> flat_;
};

constexpr std::uint32_t kRoot = std::numeric_limits<std::uint32_t>::max();

// A breadth-first spanning forest of the live tets (adjacency through
// faces), as positions into `slots`: `order` lists every tet after its
// parent; parent[i] is kRoot for the first tet of each component.
struct Forest {
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> parent;
};

Forest spanning_forest(const Mesh& mesh, const std::vector<Index>& slots) {
  std::vector<std::uint32_t> position_of(mesh.tet_slots(), kRoot);
  for (std::size_t i = 0; i < slots.size(); ++i) position_of[slots[i]] = static_cast<std::uint32_t>(i);
  Forest forest{{}, std::vector<std::uint32_t>(slots.size(), kRoot)};
  forest.order.reserve(slots.size());
  std::vector<char> reached(slots.size(), 0);
  for (std::uint32_t root = 0; root < slots.size(); ++root) {
    if (reached[root] != 0) continue;
    reached[root] = 1;
    forest.order.push_back(root);
    // forest.order is the queue: it grows behind `next`.
    for (std::size_t next = forest.order.size() - 1; next < forest.order.size(); ++next) {
      const std::uint32_t i = forest.order[next];
      for (int k = 0; k < 4; ++k) {
        const Index n = mesh.neighbour(slots[i], k);
        if (n == kNoTet || !mesh.tet_alive(n) || reached[position_of[n]] != 0) continue;
        reached[position_of[n]] = 1;
        forest.parent[position_of[n]] = i;
        forest.order.push_back(position_of[n]);
      }
    }
  }
  return forest;
}

// Per face side (4 * tet + face), the signed number of copies of the face
// in `surface`: +1 for each copy whose normal points out of that tet.
std::vector<int> face_copies(const Mesh& mesh, const TriangleSoup& surface,
                             std::span<const FaceRef> origins) {
  std::vector<int> copies(4 * mesh.tet_slots(), 0);
  for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
    const auto [t, k] = origins[i];
    const auto face = mesh.face_vertices(t, k);
    const auto& at = [&](int c) -> const Vec3d& { return surface.positions[surface.triangles[i][c]]; };
    int first = 0;
    while (first < 3 && mesh.position(face[first]).approx != at(0)) ++first;
    if (first == 3) throw UsageError("a tracked-surface triangle is not the face it came from");
    const int sign = mesh.position(face[(first + 1) % 3]).approx == at(1) ? 1 : -1;
    copies[4 * t + k] += sign;
    if (const Index n = mesh.neighbour(t, k); n != kNoTet) copies[4 * n + mesh.face_towards(n, t)] -= sign;
  }
  return copies;
}

// Whether each centroid lies strictly inside its tet (exactly).
std::vector<char> centroids_inside(const Mesh& mesh, const std::vector<Index>& slots,
                                   const std::vector<Vec3d>& centroids) {
  std::vector<char> inside(slots.size(), 0);
  tbb::parallel_for(std::size_t{0}, slots.size(), [&](std::size_t i) {
    std::array<Vec3d, 4> c;
    for (int k = 0; k < 4; ++k) c[k] = mesh.position(mesh.tet(slots[i])[k]).approx;
    bool strictly = true;
    for (int k = 0; k < 4 && strictly; ++k) {
      std::array<Vec3d, 4> with = c;
      with[k] = centroids[i];
      strictly = orient3d(with[0], with[1], with[2], with[3]) > 0;
    }
    inside[i] = strictly;
  });
  return inside;
}

constexpr int kUnknown = std::numeric_limits<int>::min();

// The winding number of `surface` at `points`: summed triangle by triangle
// for a few points (usually one per component), from a tree for more.
std::vector<double> winding_numbers(const TriangleSoup& surface, const std::vector<Vec3d>& points) {
  constexpr std::size_t kTreeFrom = 16;
  if (points.size() >= kTreeFrom) return WindingNumberTree(surface).evaluate(points);
  std::vector<double> values;
  for (const Vec3d& p : points) values.push_back(winding_number_exact(surface, p));
  return values;
}

// What the winding number of surface - cap gains from tet t to its
// neighbour u, their centroids a and b: the face between them is the only
// part of the surface the segment can cross when a and b lie inside their
// tets and it passes through the face's interior. kUnknown otherwise, or
// when it touches a cap triangle without crossing it.
int jump_through_face(const Mesh& mesh, Index t, Index u, const Vec3d& a, const Vec3d& b, bool ends_inside,
                      const std::vector<int>& copies, const CrossingCounter& cap,
                      std::vector<std::uint32_t>& scratch) {
  if (!ends_inside) return kUnknown;
  const int k = mesh.face_towards(t, u);
  const auto f = mesh.face_vertices(t, k);
  const std::optional<int> through =
      crossing(mesh.position(f[0]).approx, mesh.position(f[1]).approx, mesh.position(f[2]).approx, a, b);
  if (!through || *through == 0) return kUnknown;
  const std::optional<int> capped = cap.count(a, b, scratch);
  if (!capped) return kUnknown;
  // The copies whose normal points out of t, into u, are passed from back
  // to front: each takes one off.
  return -copies[4 * t + k] - *capped;
}

// Per live tet (positions into `slots`), what the winding number of
// surface - cap gains from its parent in the forest; kUnknown for the roots
// and where no count decides it.
std::vector<int> jumps_from_parents(const Mesh& mesh, const TriangleSoup& surface,
                                    std::span<const FaceRef> origins, const std::vector<Index>& slots,
                                    const std::vector<Vec3d>& centroids, const Forest& forest,
                                    const TriangleSoup& cap_soup, OpenWindingStats& stats) {
  const CrossingCounter cap_crossings(cap_soup);
  const std::vector<int> copies = face_copies(mesh, surface, origins);
  const std::vector<char> inside = centroids_inside(mesh, slots, centroids);
  std::vector<int> jump(slots.size(), kUnknown);
  const auto for_children = [&](auto&& carry) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slots.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<std::uint32_t> scratch;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          if (forest.parent[i] != kRoot) carry(forest.parent[i], i, scratch);
                        }
                      });
  };
  for_children([&](std::uint32_t p, std::size_t i, std::vector<std::uint32_t>& scratch) {
    jump[i] = jump_through_face(mesh, slots[p], slots[i], centroids[p], centroids[i], inside[p] && inside[i],
                                copies, cap_crossings, scratch);
  });
  // The others against the whole surface.
  stats.full_crossing_tests = static_cast<std::size_t>(
      std::count_if(forest.parent.begin(), forest.parent.end(), [&](std::uint32_t p) { return p != kRoot; }));
  stats.full_crossing_tests -=
      static_cast<std::size_t>(std::count_if(jump.begin(), jump.end(), [](int j) { return j != kUnknown; }));
  if (stats.full_crossing_tests == 0) return jump;
  const CrossingCounter surface_crossings(surface);
  for_children([&](std::uint32_t p, std::size_t i, std::vector<std::uint32_t>& scratch) {
    if (jump[i] != kUnknown) return;
    const std::optional<int> crossed = surface_crossings.count(centroids[p], centroids[i], scratch);
    const std::optional<int> cap_crossed =
        crossed ? cap_crossings.count(centroids[p], centroids[i], scratch) : std::nullopt;
    if (cap_crossed) jump[i] = *crossed - *cap_crossed;
  });
  return jump;
}

}  // namespace

std::vector<double> open_surface_winding(const Mesh& mesh, const TriangleSoup& surface,
                                         std::span<const FaceRef> origins, OpenWindingStats& stats) {
  std::vector<Index> slots;
  for (Index t = 0; t < mesh.tet_slots(); ++t)
    if (mesh.tet_alive(t)) slots.push_back(t);
  std::vector<Vec3d> centroids(slots.size());
  tbb::parallel_for(std::size_t{0}, slots.size(),
                    [&](std::size_t i) { centroids[i] = tet_centroid(mesh, slots[i]); });

  const TriangleSoup cap_soup = cap(surface);
  stats.cap_triangles = cap_soup.triangles.size();
  const std::vector<double> capped = WindingNumberTree(cap_soup).evaluate(centroids);
  const Forest forest = spanning_forest(mesh, slots);
  const std::vector<int> jump =
      jumps_from_parents(mesh, surface, origins, slots, centroids, forest, cap_soup, stats);

  // Where no count reached, the surface itself, rounded: w_S - w_D is an
  // integer there. Elsewhere the integer is the parent's plus the jump.
  std::vector<std::uint32_t> direct;
  std::vector<Vec3d> direct_points;
  for (std::uint32_t i = 0; i < slots.size(); ++i) {
    if (jump[i] != kUnknown) continue;
    direct.push_back(i);
    direct_points.push_back(centroids[i]);
  }
  stats.direct_queries = direct.size();
  const std::vector<double> direct_values = winding_numbers(surface, direct_points);
  std::vector<long> whole(slots.size(), 0);
  for (std::size_t d = 0; d < direct.size(); ++d)
    whole[direct[d]] = std::lround(direct_values[d] - capped[direct[d]]);
  for (const std::uint32_t i : forest.order)
    if (jump[i] != kUnknown) whole[i] = whole[forest.parent[i]] + jump[i];

  std::vector<double> winding(mesh.tet_slots(), 0.0);
  for (std::size_t i = 0; i < slots.size(); ++i)
    winding[slots[i]] = static_cast<double>(whole[i]) + capped[i];
  return winding;
}

}  // namespace mr::tetmesh
