#include "coplanar_polygons.h"

#include "inserter_keys.h"

#include <mr/kernel/hybrid_point.h>

#include <algorithm>
#include <unordered_map>

namespace mr::tetmesh::detail {
namespace {

// The triangles using each edge: how many, and the first two.
struct EdgeUse {
  std::uint32_t count = 0;
  std::array<std::uint32_t, 2> triangles{};
};

std::unordered_map<std::uint64_t, EdgeUse> edge_uses(std::span<const std::array<Index, 3>> triangles) {
  std::unordered_map<std::uint64_t, EdgeUse> uses;
  uses.reserve(triangles.size() * 3 / 2);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& f = triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (f[k] == f[(k + 1) % 3]) continue;
      EdgeUse& use = uses[segment_key(f[k], f[(k + 1) % 3])];
      if (use.count < 2) use.triangles[use.count] = static_cast<std::uint32_t>(t);
      ++use.count;
    }
  }
  return uses;
}

// Grows one polygon from triangle `seed` over the triangles not yet taken.
class PolygonGrower {
 public:
  PolygonGrower(const Mesh& mesh, std::span<const std::array<Index, 3>> triangles,
                std::span<const char> eligible, const std::unordered_map<std::uint64_t, EdgeUse>& uses,
                std::vector<std::uint32_t>& polygon_of)
      : mesh_(mesh), triangles_(triangles), eligible_(eligible), uses_(uses), polygon_of_(polygon_of) {}

  ConvexPolygon grow(std::uint32_t seed, std::size_t max_corners) {
    const auto& f = triangles_[seed];
    ConvexPolygon polygon{{f[0], f[1], f[2]}, seed};
    polygon_of_[seed] = seed;
    if (!choose_projection(f)) return polygon;  // collinear corners: insertion skips it
    bool grown = true;
    while (grown && polygon.corners.size() < max_corners) {
      grown = false;
      for (std::size_t e = 0; e < polygon.corners.size() && !grown; ++e) grown = grow_across(polygon, e);
    }
    return polygon;
  }

 private:
  const HybridPoint& at(Index v) const { return mesh_.position(v); }

  // A projection axis along which the seed keeps its area, and the sign of
  // its orientation there (that of every strictly convex corner).
  bool choose_projection(const std::array<Index, 3>& f) {
    for (axis_ = 0; axis_ < 3; ++axis_) {
      orientation_ = orient2d_projected(at(f[0]), at(f[1]), at(f[2]), axis_);
      if (orientation_ != 0) {
        plane_ = f;
        return true;
      }
    }
    return false;
  }

  bool strictly_convex(Index a, Index b, Index c) const {
    return orientation_ * orient2d_projected(at(a), at(b), at(c), axis_) > 0;
  }

  // Adds the triangle across polygon edge e (corners e, e+1) if it is free,
  // coplanar, oriented alike (by its indices and by its corners) and keeps
  // the polygon strictly convex.
  bool grow_across(ConvexPolygon& polygon, std::size_t e) {
    std::vector<Index>& corners = polygon.corners;
    const std::size_t n = corners.size();
    const Index u = corners[e];
    const Index v = corners[(e + 1) % n];
    const auto found = uses_.find(segment_key(u, v));
    if (found == uses_.end() || found->second.count != 2) return false;
    const auto [t0, t1] = found->second.triangles;
    const std::uint32_t other = polygon_of_[t0] == polygon.id ? t1 : t0;
    if (!eligible_[other] || polygon_of_[other] != CoplanarGrouping::kNotGrouped) return false;
    const auto& g = triangles_[other];
    Index d = kNoVertex;
    for (int k = 0; k < 3; ++k) {
      if (g[k] == v && g[(k + 1) % 3] == u) d = g[(k + 2) % 3];  // runs v -> u: same orientation
    }
    if (d == kNoVertex || std::find(corners.begin(), corners.end(), d) != corners.end()) return false;
    if (orient3d(at(plane_[0]), at(plane_[1]), at(plane_[2]), at(d)) != 0) return false;
    // d must lie outside edge (u, v): a triangle folded back over the
    // polygon is oriented alike only by its indices, and its chain
    // subtracts where the polygon's adds (openscad-nonmanifold-crash).
    if (!strictly_convex(u, d, v)) return false;
    const Index before = corners[(e + n - 1) % n];
    const Index after = corners[(e + 2) % n];
    if (!strictly_convex(before, u, d) || !strictly_convex(d, v, after)) return false;
    corners.insert(corners.begin() + static_cast<std::ptrdiff_t>(e + 1), d);
    polygon_of_[other] = polygon.id;
    return true;
  }

  const Mesh& mesh_;
  std::span<const std::array<Index, 3>> triangles_;
  std::span<const char> eligible_;
  const std::unordered_map<std::uint64_t, EdgeUse>& uses_;
  std::vector<std::uint32_t>& polygon_of_;
  std::array<Index, 3> plane_{};
  int axis_ = 0;
  int orientation_ = 0;
};

}  // namespace

CoplanarGrouping group_coplanar_triangles(const Mesh& mesh, std::span<const std::array<Index, 3>> triangles,
                                          std::span<const char> eligible, std::size_t max_corners) {
  CoplanarGrouping grouping;
  grouping.polygon_of.assign(triangles.size(), CoplanarGrouping::kNotGrouped);
  const auto uses = edge_uses(triangles);
  PolygonGrower grower(mesh, triangles, eligible, uses, grouping.polygon_of);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!eligible[t] || grouping.polygon_of[t] != CoplanarGrouping::kNotGrouped) continue;
    grouping.polygons.push_back(grower.grow(static_cast<std::uint32_t>(t), max_corners));
  }
  return grouping;
}

}  // namespace mr::tetmesh::detail
