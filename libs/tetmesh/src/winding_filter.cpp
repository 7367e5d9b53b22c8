#include <mr/tetmesh/winding_filter.h>

#include "regions.h"

#include <mr/core/errors.h>
#include <mr/spatial/aabb_tree.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <string>

namespace mr::tetmesh {

Vec3d tet_centroid(const Mesh& mesh, Index t) {
  const Tet& c = mesh.tet(t);
  return 0.25 * (mesh.position(c[0]).approx + mesh.position(c[1]).approx + mesh.position(c[2]).approx +
                 mesh.position(c[3]).approx);
}

double tet_approx_volume6(const Mesh& mesh, Index t) {
  const Tet& c = mesh.tet(t);
  const Vec3d& a = mesh.position(c[0]).approx;
  return (mesh.position(c[1]).approx - a)
      .cross(mesh.position(c[2]).approx - a)
      .dot(mesh.position(c[3]).approx - a);
}

bool is_inside(double winding, WindingRule rule) {
  return (rule == WindingRule::absolute ? std::abs(winding) : winding) > 0.5;
}

namespace {

// The classification of the live tets `slots`, slots[i] having winding
// number winding_of(i); winding_of is called once per i, in order.
template <class WindingOf>
TetClassification classification(const Mesh& mesh, std::span<const Index> slots, WindingRule rule,
                                 WindingOf&& winding_of) {
  TetClassification result;
  result.winding.assign(mesh.tet_slots(), 0.0);
  result.keep.assign(mesh.tet_slots(), 0);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    const double w = winding_of(i);
    result.winding[slots[i]] = w;
    if (is_inside(w, rule)) {
      result.keep[slots[i]] = 1;
      ++result.kept;
    }
  }
  return result;
}

std::vector<Index> live_tets(const Mesh& mesh) {
  std::vector<Index> slots;
  slots.reserve(mesh.num_tets());
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t)) slots.push_back(t);
  }
  return slots;
}

}  // namespace

TetClassification classify_tets(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule) {
  const std::vector<Index> slots = live_tets(mesh);
  std::vector<Vec3d> centroids;
  centroids.reserve(slots.size());
  for (const Index t : slots) centroids.push_back(tet_centroid(mesh, t));
  const std::vector<double> values = tree.evaluate(centroids);
  return classification(mesh, slots, rule, [&](std::size_t i) { return values[i]; });
}

TetClassification classify_by_winding(const Mesh& mesh, std::span<const double> winding, WindingRule rule) {
  const std::vector<Index> slots = live_tets(mesh);
  return classification(mesh, slots, rule, [&](std::size_t i) { return winding[slots[i]]; });
}

std::vector<double> tracked_surface_offsets(const Mesh& mesh, const TriangleSoup& input) {
  std::vector<double> offsets(input.triangles.size(), 0.0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int k = 0; k < 4; ++k) {
      if (!mesh.is_surface_face(t, k)) continue;
      const auto corners = mesh.face_vertices(t, k);
      for (const std::uint32_t id : mesh.surface_ids(t, k)) {
        const Vec3d normal = detail::input_normal(input, id);
        if (normal.squaredNorm() == 0.0) continue;  // a degenerate triangle adds nothing to the chain
        const Vec3d& origin = input.positions[input.triangles[id][0]];
        for (const Index v : corners) {
          offsets[id] = std::max(offsets[id], std::abs((mesh.position(v).approx - origin).dot(normal)));
        }
      }
    }
  }
  return offsets;
}

namespace {

// Whether points lie within kOffsetMargin times its offset of some
// triangle: the triangles grouped by the binary exponent of their offset,
// so that one far-moved point does not widen the guard of all the others.
class OffsetGuard {
 public:
  OffsetGuard(const TriangleSoup& input, std::span<const char> left_out, std::span<const double> offsets) {
    std::map<int, TriangleSoup> groups;
    std::map<int, double> radii;
    for (std::size_t i = 0; i < input.triangles.size(); ++i) {
      if (left_out[i] != 0) continue;
      const int exponent = offsets[i] > 0.0 ? std::ilogb(offsets[i]) : std::numeric_limits<int>::min();
      TriangleSoup& group = groups[exponent];
      for (const Index v : input.triangles[i]) group.positions.push_back(input.positions[v]);
      const Index base = static_cast<Index>(group.positions.size() - 3);
      group.triangles.push_back({base, base + 1, base + 2});
      radii[exponent] = std::max(radii[exponent], kOffsetMargin * offsets[i]);
    }
    for (const auto& [exponent, group] : groups) {
      trees_.emplace_back(group);
      radii_.push_back(radii[exponent]);
    }
  }

  bool near(const Vec3d& p) const {
    for (std::size_t g = 0; g < trees_.size(); ++g) {
      if (trees_[g].any_within(p, radii_[g])) return true;
    }
    return false;
  }

 private:
  std::vector<spatial::AabbTree> trees_;
  std::vector<double> radii_;
};

}  // namespace

TetClassification classify_tets_near_input(const Mesh& mesh, const WindingNumberTree& tracked,
                                           const TriangleSoup& input, std::span<const char> left_out,
                                           std::span<const double> offsets, WindingRule rule,
                                           std::size_t* near_queries) {
  const std::vector<Index> slots = live_tets(mesh);
  const OffsetGuard guard(input, left_out, offsets);
  std::vector<Vec3d> centroids(slots.size());
  std::vector<char> near(slots.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slots.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        centroids[i] = tet_centroid(mesh, slots[i]);
                        near[i] = guard.near(centroids[i]);
                      }
                    });
  std::vector<Vec3d> far_points, near_points;
  for (std::size_t i = 0; i < slots.size(); ++i) (near[i] ? near_points : far_points).push_back(centroids[i]);
  TriangleSoup chain;
  chain.positions = input.positions;
  for (std::size_t i = 0; i < input.triangles.size(); ++i) {
    if (left_out[i] == 0) chain.triangles.push_back(input.triangles[i]);
  }
  const std::vector<double> far_values = WindingNumberTree(chain).evaluate(far_points);
  const std::vector<double> near_values = tracked.evaluate(near_points);
  if (near_queries != nullptr) *near_queries = near_points.size();

  std::size_t next_far = 0, next_near = 0;
  return classification(mesh, slots, rule, [&](std::size_t i) {
    return near[i] ? near_values[next_near++] : far_values[next_far++];
  });
}

std::vector<double> open_tracked_winding(const Mesh& mesh, const TriangleSoup& tracked,
                                         std::span<const FaceRef> origins, std::size_t boundary_edges,
                                         const TriangleSoup& input, std::span<const char> left_out,
                                         OpenSurfaceStats& stats) {
  const auto input_triangles = static_cast<std::size_t>(std::count(left_out.begin(), left_out.end(), 0));
  stats.by_crossings = boundary_edges <= input_triangles;
  if (stats.by_crossings) return open_surface_winding(mesh, tracked, origins, stats.crossings);
  return classify_tets_near_input(mesh, WindingNumberTree(tracked), input, left_out,
                                  tracked_surface_offsets(mesh, input), WindingRule::absolute,
                                  &stats.near_queries)
      .winding;
}

std::vector<char> tets_near(const Mesh& mesh, const TriangleSoup& triangles) {
  std::vector<char> near(mesh.tet_slots(), 0);
  if (triangles.triangles.empty()) return near;
  const spatial::AabbTree tree(triangles);
  tbb::parallel_for(tbb::blocked_range<Index>(0, static_cast<Index>(mesh.tet_slots()), 256),
                    [&](const tbb::blocked_range<Index>& range) {
                      for (Index t = range.begin(); t != range.end(); ++t) {
                        if (!mesh.tet_alive(t)) continue;
                        const Vec3d centre = tet_centroid(mesh, t);
                        double radius = 0.0;
                        for (const Index v : mesh.tet(t)) {
                          radius = std::max(radius, (mesh.position(v).approx - centre).norm());
                        }
                        // Doubled: the corners' doubles and the distance are rounded.
                        near[t] = tree.any_within(centre, 2.0 * radius);
                      }
                    });
  return near;
}

namespace {

// tree.evaluate(queries), reusing the values of points asked before.
std::vector<double> evaluate_cached(const WindingNumberTree& tree, const std::vector<Vec3d>& queries,
                                    WindingCache* cache) {
  if (cache == nullptr) return tree.evaluate(queries);
  const auto key = [](const Vec3d& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  std::vector<Vec3d> missing;
  for (const Vec3d& q : queries) {
    if (!cache->contains(key(q))) missing.push_back(q);
  }
  const std::vector<double> values = tree.evaluate(missing);
  for (std::size_t i = 0; i < missing.size(); ++i) cache->emplace(key(missing[i]), values[i]);
  std::vector<double> out;
  out.reserve(queries.size());
  for (const Vec3d& q : queries) out.push_back(cache->at(key(q)));
  return out;
}

}  // namespace

TetClassification classify_regions(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule,
                                   std::span<const char> barrier, WindingCache* cache) {
  const std::vector<std::int32_t> labels = detail::region_labels(mesh, barrier);
  const std::int32_t regions = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end());
  std::vector<Index> largest(static_cast<std::size_t>(regions) + 1, kNoTet);
  std::vector<double> largest_volume(largest.size(), -1.0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const double volume = tet_approx_volume6(mesh, t);
    if (volume > largest_volume[labels[t]]) {
      largest_volume[labels[t]] = volume;
      largest[labels[t]] = t;
    }
  }
  std::vector<Vec3d> queries;
  for (std::int32_t r = 1; r <= regions; ++r) queries.push_back(tet_centroid(mesh, largest[r]));
  const std::vector<double> values = evaluate_cached(tree, queries, cache);
  const std::vector<Index> slots = live_tets(mesh);
  return classification(mesh, slots, rule, [&](std::size_t i) { return values[labels[slots[i]] - 1]; });
}

TetMesh extract_tets(const Mesh& mesh, std::span<const char> keep) {
  if (keep.size() != mesh.tet_slots()) {
    throw UsageError("extract_tets: " + std::to_string(keep.size()) + " flags for " +
                     std::to_string(mesh.tet_slots()) + " tet slots");
  }
  std::vector<Index> new_index(mesh.vertex_slots(), kNoVertex);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!keep[t]) continue;
    if (!mesh.tet_alive(t)) throw UsageError("extract_tets: removed tet " + std::to_string(t) + " kept");
    for (const Index v : mesh.tet(t)) new_index[v] = 0;
  }
  TetMesh out;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (new_index[v] == kNoVertex) continue;
    if (mesh.position(v).is_exact()) {
      throw RunError("extract_tets: vertex " + std::to_string(v) + " of a kept tet is still rational");
    }
    new_index[v] = static_cast<Index>(out.positions.size());
    out.positions.push_back(mesh.position(v).approx);
  }
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!keep[t]) continue;
    Tet tet = mesh.tet(t);
    for (Index& v : tet) v = new_index[v];
    out.tets.push_back(tet);
  }
  return out;
}

}  // namespace mr::tetmesh
