#include <mr/core/grid_snap.h>

#include <cassert>
#include <cmath>

namespace mr {

double power_of_two_at_most(double bound) {
  assert(std::isnormal(bound) && bound > 0);
  int exponent = 0;
  std::frexp(bound, &exponent);  // bound = m * 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, exponent - 1);
}

std::size_t snap_to_grid(TriangleSoup& soup, double spacing) {
  std::size_t moved = 0;
  for (Vec3d& p : soup.positions) {
    const Vec3d before = p;
    // Dividing and multiplying by a power of two is exact, so the result
    // is the grid point nearest to p.
    for (int axis = 0; axis < 3; ++axis) p[axis] = std::nearbyint(p[axis] / spacing) * spacing;
    moved += p != before;
  }
  return moved;
}

}  // namespace mr
