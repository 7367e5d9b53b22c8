#include <mr/kernel/point_box.h>

#include <CGAL/Interval_nt.h>

#include <array>
#include <cmath>
#include <limits>

namespace mr {
namespace {

using Interval = CGAL::Interval_nt<false>;  // rounding set once per function
using IntervalPoint = std::array<Interval, 3>;

IntervalPoint to_interval(const PointBox& box) {
  return {Interval(box.lo.x(), box.hi.x()), Interval(box.lo.y(), box.hi.y()),
          Interval(box.lo.z(), box.hi.z())};
}

int certain_sign(const Interval& value) {
  if (value.inf() > 0) return 1;
  if (value.sup() < 0) return -1;
  if (value.inf() == 0 && value.sup() == 0) return 0;
  return kUncertainSign;
}

// Six times the signed volume of (p, q, r, x).
Interval volume(const IntervalPoint& p, const IntervalPoint& q, const IntervalPoint& r,
                const IntervalPoint& x) {
  Interval u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = q[k] - p[k];
    v[k] = r[k] - p[k];
    w[k] = x[k] - p[k];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

}  // namespace

PointBox box_of(const HybridPoint& p) {
  if (!p.exact) return {p.approx, p.approx};
  constexpr double inf = std::numeric_limits<double>::infinity();
  PointBox box;
  for (int k = 0; k < 3; ++k) {
    box.lo[k] = std::nextafter(p.approx[k], -inf);
    box.hi[k] = std::nextafter(p.approx[k], inf);
  }
  return box;
}

std::optional<PointBox> box_of_segment_plane(const HybridPoint& a, const HybridPoint& b, const HybridPoint& p,
                                             const HybridPoint& q, const HybridPoint& r) {
  const CGAL::Protect_FPU_rounding<true> upward;
  const IntervalPoint ia = to_interval(box_of(a)), ib = to_interval(box_of(b));
  const IntervalPoint ip = to_interval(box_of(p)), iq = to_interval(box_of(q)), ir = to_interval(box_of(r));
  const Interval va = volume(ip, iq, ir, ia);
  const Interval vb = volume(ip, iq, ir, ib);
  const Interval denominator = va - vb;
  if (denominator.inf() <= 0 && denominator.sup() >= 0) return std::nullopt;
  // t = va / (va - vb) lies in [0, 1] for a crossing segment: clamp the
  // enclosure to it (both are valid enclosures, so is their intersection).
  Interval t = va / denominator;
  t = Interval(std::max(t.inf(), 0.0), std::min(t.sup(), 1.0));
  if (t.inf() > t.sup()) return std::nullopt;
  PointBox box;
  for (int k = 0; k < 3; ++k) {
    const Interval x = ia[k] + t * (ib[k] - ia[k]);
    if (!std::isfinite(x.inf()) || !std::isfinite(x.sup())) return std::nullopt;
    box.lo[k] = x.inf();
    box.hi[k] = x.sup();
  }
  return box;
}

int orient2d_projected(const PointBox& a, const PointBox& b, const PointBox& c, int axis) {
  const CGAL::Protect_FPU_rounding<true> upward;
  const int i = axis == 0 ? 1 : 0;
  const int j = axis == 2 ? 1 : 2;
  const IntervalPoint ia = to_interval(a), ib = to_interval(b), ic = to_interval(c);
  return certain_sign((ib[i] - ia[i]) * (ic[j] - ia[j]) - (ib[j] - ia[j]) * (ic[i] - ia[i]));
}

}  // namespace mr
