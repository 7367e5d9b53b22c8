// Predicates on hybrid points. With at least one rational point, CGAL's
// interval arithmetic (directed rounding, so the enclosure is certain)
// decides the sign when it can; GMP evaluates the rest exactly. The interval
// of a rational coordinate comes from the HybridPoint invariant (approx is
// its nearest double, so the rational lies between approx's neighbours)
// without touching GMP.

#include <mr/kernel/hybrid_point.h>

#include <CGAL/Interval_nt.h>

#include <array>
#include <cmath>
#include <limits>

namespace mr {
namespace {

using Interval = CGAL::Interval_nt<false>;  // rounding set once per predicate
using IntervalPoint = std::array<Interval, 3>;

Interval around(double nearest) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {std::nextafter(nearest, -inf), std::nextafter(nearest, inf)};
}

IntervalPoint to_interval(const HybridPoint& p) {
  if (!p.exact) return {Interval(p.approx.x()), Interval(p.approx.y()), Interval(p.approx.z())};
  return {around(p.approx.x()), around(p.approx.y()), around(p.approx.z())};
}

/// The sign when the enclosure certifies it, otherwise 2.
constexpr int kUncertain = 2;
int certain_sign(const Interval& value) {
  if (value.inf() > 0) return 1;
  if (value.sup() < 0) return -1;
  if (value.inf() == 0 && value.sup() == 0) return 0;
  return kUncertain;
}

int filtered_orient3d(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c,
                      const HybridPoint& d) {
  const CGAL::Protect_FPU_rounding<true> upward;
  const IntervalPoint ia = to_interval(a), ib = to_interval(b), ic = to_interval(c), id = to_interval(d);
  Interval u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = ib[k] - ia[k];
    v[k] = ic[k] - ia[k];
    w[k] = id[k] - ia[k];
  }
  const Interval det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                       u[2] * (v[0] * w[1] - v[1] * w[0]);
  return certain_sign(det);
}

int filtered_orient2d(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c, int i, int j) {
  const CGAL::Protect_FPU_rounding<true> upward;
  const IntervalPoint ia = to_interval(a), ib = to_interval(b), ic = to_interval(c);
  const Interval det = (ib[i] - ia[i]) * (ic[j] - ia[j]) - (ib[j] - ia[j]) * (ic[i] - ia[i]);
  return certain_sign(det);
}

}  // namespace

HybridPoint HybridPoint::from_exact(ExactPoint3 p) {
  HybridPoint result(round_to_nearest(p));
  if (!is_representable(p)) result.exact = std::move(p);
  return result;
}

bool operator==(const HybridPoint& a, const HybridPoint& b) {
  if (!a.exact && !b.exact) return a.approx == b.approx;
  return a.to_exact() == b.to_exact();
}

int orient3d(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c, const HybridPoint& d) {
  if (!a.exact && !b.exact && !c.exact && !d.exact) return orient3d(a.approx, b.approx, c.approx, d.approx);
  const int sign = filtered_orient3d(a, b, c, d);
  if (sign != kUncertain) return sign;
  return orient3d(a.to_exact(), b.to_exact(), c.to_exact(), d.to_exact());
}

int orient2d_projected(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c, int axis) {
  if (!a.exact && !b.exact && !c.exact) return orient2d_projected(a.approx, b.approx, c.approx, axis);
  const int i = axis == 0 ? 1 : 0;
  const int j = axis == 2 ? 1 : 2;
  const int sign = filtered_orient2d(a, b, c, i, j);
  if (sign != kUncertain) return sign;
  return orient2d_projected(a.to_exact(), b.to_exact(), c.to_exact(), axis);
}

}  // namespace mr
