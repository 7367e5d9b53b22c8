#include <mr/core/thicken.h>

#include <array>

namespace mr {
namespace {

void add_prism(const std::array<Vec3d, 3>& corner, const Vec3d& offset, TriangleSoup& out) {
  const auto first = static_cast<Index>(out.positions.size());
  for (const Vec3d& p : corner) out.positions.push_back(p - offset);  // bottom: first + i
  for (const Vec3d& p : corner) out.positions.push_back(p + offset);  // top: first + 3 + i
  const auto bottom = [&](int i) { return first + Index(i); };
  const auto top = [&](int i) { return first + 3 + Index(i); };
  out.triangles.push_back({top(0), top(1), top(2)});
  out.triangles.push_back({bottom(0), bottom(2), bottom(1)});
  // The wall on edge (i, j) faces away from the third corner: for a
  // counter-clockwise triangle that is (j - i) x normal.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    out.triangles.push_back({bottom(i), bottom(j), top(j)});
    out.triangles.push_back({bottom(i), top(j), top(i)});
  }
}

}  // namespace

TriangleSoup thicken_sheets(const TriangleSoup& soup, double half_thickness) {
  TriangleSoup out;
  out.positions.reserve(6 * soup.triangles.size());
  out.triangles.reserve(8 * soup.triangles.size());
  for (const Triangle& t : soup.triangles) {
    const std::array<Vec3d, 3> corner{soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]};
    const Vec3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
    const double length = normal.norm();
    if (!(length > 0.0)) continue;
    add_prism(corner, normal * (half_thickness / length), out);
  }
  return out;
}

}  // namespace mr
