#include <mr/winding_number/winding_number.h>

#include <cmath>
#include <numbers>

namespace mr {

double signed_solid_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& q) {
  if ((b - a).cross(c - a).squaredNorm() == 0.0) return 0.0;
  Vec3d u = a - q, v = b - q, w = c - q;
  const double lu = u.norm(), lv = v.norm(), lw = w.norm();
  if (lu == 0.0 || lv == 0.0 || lw == 0.0) return 0.0;
  // Normalizing first keeps the products in range for huge coordinates; the
  // formula tan(omega/2) = det / (1 + u.v + v.w + w.u) then holds for unit vectors.
  u /= lu;
  v /= lv;
  w /= lw;
  const double det = u.dot(v.cross(w));
  const double den = 1.0 + u.dot(v) + v.dot(w) + w.dot(u);
  return 2.0 * std::atan2(det, den);
}

double winding_number_exact(const TriangleSoup& soup, const Vec3d& q) {
  double sum = 0.0;
  for (const Triangle& t : soup.triangles)
    sum += signed_solid_angle(soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]], q);
  return sum / (4.0 * std::numbers::pi);
}

}  // namespace mr
