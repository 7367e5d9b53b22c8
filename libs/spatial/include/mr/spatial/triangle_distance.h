#pragma once
// Closest points on segments and triangles, in doubles.

#include <mr/core/types.h>

namespace mr::spatial {

struct PointOnPrimitive {
  Vec3d point;
  double squared_distance = 0.0;
};

/// Closest point of segment [a, b] to p; a zero-length segment is the point a.
PointOnPrimitive closest_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b);

/// Closest point of triangle (a, b, c) to p. Degenerate triangles (segments,
/// points) are handled: when the triangle is thinner than about 1e-6 of its
/// longest edge (its normal cannot be trusted) the answer is the closest point
/// of its three edges, which overestimates the distance by at most its width.
/// The returned point always lies on the triangle up to rounding.
PointOnPrimitive closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

/// Squared distance from p to triangle (a, b, c), the same as
/// closest_on_triangle's up to rounding but faster: the region of p
/// (vertex, edge or face) is found from six dot products, and only that
/// feature's distance is computed. For the hot loops of distance queries.
double squared_distance_to_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace mr::spatial
