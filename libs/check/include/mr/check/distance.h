#pragma once
// Sampled one-sided distances between surfaces (Hausdorff estimates).

#include <mr/core/triangle_soup.h>

namespace mr::check {

struct DistanceReport {
  double max = 0;  ///< largest sample distance found
  double mean = 0;
  Vec3d farthest = Vec3d::Zero();  ///< the sample at distance max: where to look
  std::size_t samples = 0;
};

struct DistanceOptions {
  /// Samples per unit area relative to the bounding-box diagonal b: a face of
  /// area A gets about density * A / b^2 interior samples, plus its corners
  /// and edge midpoints. Deterministic (fixed seed).
  double density = 2e5;
  std::size_t max_samples = 2000000;
};

/// Distances from points of `from` to the surface `to`.
DistanceReport one_sided_distance(const TriangleSoup& from, const TriangleSoup& to,
                                  const DistanceOptions& options = {});

/// Whether every sample of `from` (one_sided_distance's) lies within
/// `distance` of `to`: one_sided_distance(from, to).max <= distance, but
/// each query stops at the first triangle that close, and all stop at the
/// first sample farther. A face one triangle of `to` is that close to at
/// all three corners is within as a whole (distance to a triangle is
/// convex), and its samples are not asked.
bool lies_within(const TriangleSoup& from, const TriangleSoup& to, double distance,
                 const DistanceOptions& options = {});

}  // namespace mr::check
