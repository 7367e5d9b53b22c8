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

PointOnPrimitive closest_on_edges(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
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
PointOnPrimitive closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
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
  const bool inside =
      ab.cross(pa).dot(normal) >= 0.0 && bc.cross(pb).dot(normal) >= 0.0 && ca.cross(pc).dot(normal) >= 0.0;
  if (!inside) return closest_on_edges(p, a, b, c);
  const double height = pa.dot(normal);
  const Vec3d q = p - (height / normal_sq) * normal;
  return {q, height * height / normal_sq};
}

// Voronoi regions of the corners and edges by the signs of dot products
// (as in Ericson, Real-Time Collision Detection, 5.1.5); the face region
// takes the distance to the plane, which needs no division by the
// barycentric denominator. Thin triangles take the edge path above.
double squared_distance_to_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a;
  const Vec3d ac = c - a;
  const Vec3d normal = ab.cross(ac);
  const double normal_sq = normal.squaredNorm();
  const double longest_sq = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  const double min_normal = kDegenerateNormalFraction * longest_sq;
  if (!(normal_sq > min_normal * min_normal)) return closest_on_edges(p, a, b, c).squared_distance;

  const Vec3d ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.squaredNorm();
  const Vec3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.squaredNorm();
  if (d1 >= 0.0 && d3 <= 0.0 && d1 * d4 - d3 * d2 <= 0.0) return (ap - (d1 / (d1 - d3)) * ab).squaredNorm();
  const Vec3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.squaredNorm();
  if (d2 >= 0.0 && d6 <= 0.0 && d5 * d2 - d1 * d6 <= 0.0) return (ap - (d2 / (d2 - d6)) * ac).squaredNorm();
  const double e = d4 - d3, f = d5 - d6;
  if (e >= 0.0 && f >= 0.0 && d3 * d6 - d5 * d4 <= 0.0) return (bp - (e / (e + f)) * (c - b)).squaredNorm();
  const double height = normal.dot(ap);
  return height * height / normal_sq;
}

}  // namespace mr::spatial
