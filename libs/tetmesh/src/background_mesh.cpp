#include <mr/tetmesh/background_mesh.h>

#include "delaunay.h"

#include <mr/core/errors.h>
#include <mr/kernel/predicates.h>
#include <mr/kernel/rounding.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <unordered_map>
#include <unordered_set>

namespace mr::tetmesh {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct PositionHash {
  std::size_t operator()(const Vec3d& p) const {
    std::size_t h = 0;
    for (int axis = 0; axis < 3; ++axis) {
      // + 0.0 maps -0.0 to +0.0: equal values must hash alike.
      h = h * 1000003u ^ std::hash<std::uint64_t>()(std::bit_cast<std::uint64_t>(p[axis] + 0.0));
    }
    return h;
  }
};

struct PositionEqual {
  bool operator()(const Vec3d& a, const Vec3d& b) const { return a == b; }
};

// Distinct input positions in first-occurrence order, and each input vertex's slot.
std::vector<Vec3d> merge_equal_positions(const TriangleSoup& input, std::vector<Index>& input_vertex) {
  std::unordered_map<Vec3d, Index, PositionHash, PositionEqual> slot_of;
  slot_of.reserve(input.positions.size());
  std::vector<Vec3d> distinct;
  input_vertex.resize(input.positions.size());
  for (std::size_t i = 0; i < input.positions.size(); ++i) {
    const auto [it, inserted] = slot_of.try_emplace(input.positions[i], static_cast<Index>(distinct.size()));
    if (inserted) distinct.push_back(input.positions[i]);
    input_vertex[i] = it->second;
  }
  return distinct;
}

void require_box_contains(const std::vector<Vec3d>& points, const BackgroundParameters& p) {
  for (const Vec3d& v : points) {
    if ((v.array() <= p.box_min.array()).any() || (v.array() >= p.box_max.array()).any()) {
      throw UsageError("background mesh: the box must strictly contain every input vertex");
    }
  }
}

std::vector<Vec3d> box_corners(const Vec3d& lo, const Vec3d& hi) {
  std::vector<Vec3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  }
  return corners;
}

bool on_box(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  return (p.array() == lo.array()).any() || (p.array() == hi.array()).any();
}

// The even permutation of a tet with its smallest index first and, of the
// other three, the smallest second: a canonical form that keeps orientation.
Tet canonical(const Tet& t) {
  const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  std::array<Index, 3> rest = opposite_face(t, k);
  std::rotate(rest.begin(), std::min_element(rest.begin(), rest.end()), rest.end());
  return {t[k], rest[0], rest[1], rest[2]};
}

// Positively orients (exact test) and canonicalizes every tet, then sorts them.
void orient_and_sort(std::vector<Tet>& tets, const std::vector<Vec3d>& points) {
  std::atomic<bool> flat{false};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tets.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        Tet& t = tets[i];
                        const int o = orient3d(points[t[0]], points[t[1]], points[t[2]], points[t[3]]);
                        if (o == 0) flat = true;
                        if (o < 0) std::swap(t[2], t[3]);
                        t = canonical(t);
                      }
                    });
  if (flat) throw RunError("background mesh: the Delaunay triangulation produced a flat tet");
  tbb::parallel_sort(tets.begin(), tets.end());
}

}  // namespace

BackgroundMesh build_background_mesh(const TriangleSoup& input, const spatial::AabbTree& tree,
                                     const BackgroundParameters& parameters) {
  BackgroundMesh out;
  auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(parameters.threads > 0 ? parameters.threads : tbb::task_arena::automatic);

  std::vector<Vec3d> points = merge_equal_positions(input, out.input_vertex);
  out.distinct_input_vertices = points.size();
  require_box_contains(points, parameters);
  for (const Vec3d& c : box_corners(parameters.box_min, parameters.box_max)) points.push_back(c);
  if (parameters.lattice_spacing > 0.0) {
    std::vector<Vec3d> lattice;
    arena.execute([&] {
      lattice = voxel_stuffing_points(parameters.box_min, parameters.box_max, parameters.lattice_spacing,
                                      parameters.lattice_clearance, tree);
    });
    // An unreferenced input vertex is not in the tree: never insert a point twice.
    const std::unordered_set<Vec3d, PositionHash, PositionEqual> input_points(
        points.begin(), points.begin() + static_cast<std::ptrdiff_t>(out.distinct_input_vertices));
    std::erase_if(lattice, [&](const Vec3d& p) { return input_points.contains(p); });
    out.lattice_points = lattice.size();
    points.insert(points.end(), lattice.begin(), lattice.end());
  }
  out.seconds_lattice = seconds_since(start);

  start = std::chrono::steady_clock::now();
  std::vector<Tet> tets = detail::delaunay_tets(points, parameters.box_min, parameters.box_max,
                                                parameters.parallel, parameters.threads);
  out.seconds_delaunay = seconds_since(start);

  start = std::chrono::steady_clock::now();
  arena.execute([&] { orient_and_sort(tets, points); });
  out.mesh.reserve(points.size(), tets.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool box =
        i >= out.distinct_input_vertices && on_box(points[i], parameters.box_min, parameters.box_max);
    out.mesh.add_vertex(HybridPoint(points[i]), box ? kOnBox : 0);
  }
  for (const Tet& t : tets) out.mesh.add_tet(t);
  arena.execute([&] { out.mesh.rebuild_adjacency(); });
  out.seconds_mesh = seconds_since(start);
  return out;
}

}  // namespace mr::tetmesh
