#include <mr/spatial/triangle_distance.h>

#include <algorithm>

namespace mr::spatial {

PointOnPrimitive closest_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double length_sq = ab.squaredNorm();
  double t = 0.0;
  if (length_sq > 0.0) t = std::clamp((p - a).dot(ab) / length_sq, 0.0, 1.0);
  const Vec3d q = a + t * ab;
  return {q, (p - q).squaredNorm()};
}

namespace {

// A normal shorter than this fraction of the squared longest edge has an
// unreliable direction (rounding error ~ 1e-16 / fraction radians).
constexpr double kDegenerateNormalFraction = 1e-6;

PointOnPrimitive closest_on_edges(const Vec3d& p, const Vec3d& a, const Vec3d& b,
                                  const Vec3d& c) {
  PointOnPrimitive best = closest_on_segment(p, a, b);
  for (const PointOnPrimitive& candidate : {closest_on_segment(p, b, c), closest_on_segment(p, c, a)}) {
    if (candidate.squared_distance < best.squared_distance) best = candidate;
  }
  return best;
}

}  // namespace

// The projection of p onto the plane is the answer when it falls inside the
// triangle (all three edge tests non-negative); otherwise the closest point
// lies on the boundary, and the minimum over the three edges is exact. The
// edge tests are signs of triple products, so no barycentric division is
// needed and slivers cannot produce points off the triangle.
PointOnPrimitive closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b,
                                     const Vec3d& c) {
  const Vec3d ab = b - a;
  const Vec3d bc = c - b;
  const Vec3d ca = a - c;
  const Vec3d normal = ab.cross(-ca);
  const double normal_sq = normal.squaredNorm();
  const double longest_sq = std::max({ab.squaredNorm(), bc.squaredNorm(), ca.squaredNorm()});
  const double min_normal = kDegenerateNormalFraction * longest_sq;
  if (!(normal_sq > min_normal * min_normal)) return closest_on_edges(p, a, b, c);

  const Vec3d pa = p - a;
  const Vec3d pb = p - b;
  const Vec3d pc = p - c;
  const bool inside = ab.cross(pa).dot(normal) >= 0.0 && bc.cross(pb).dot(normal) >= 0.0 &&
                      ca.cross(pc).dot(normal) >= 0.0;
  if (!inside) return closest_on_edges(p, a, b, c);
  const double height = pa.dot(normal);
  const Vec3d q = p - (height / normal_sq) * normal;
  return {q, height * height / normal_sq};
}

}  // namespace mr::spatial
