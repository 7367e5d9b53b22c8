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

}  // namespace mr::check
