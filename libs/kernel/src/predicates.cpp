// Filtered exact predicates on doubles: thin wrappers over CGAL's Epick
// kernel (semi-static floating-point filter, then interval arithmetic, then
// exact multi-precision evaluation).
//
// Why CGAL and not our own Shewchuk-style filter: we wrote and measured one
// (error bound "A" with the permanent of the coordinate differences, plus
// guards for underflow and overflow, falling back to CGAL for the exact
// stage). With bench/kernel_bench.cpp, one thread, CPU time per orient3d
// call on the shared 2-core build machine (2.6 GHz), several runs:
//   random inputs:           own filter 8.8-9.1 ns, CGAL 5.4-6.0 ns
//   near-degenerate inputs:  both 430-570 ns (the exact stage dominates)
//   exactly coplanar inputs: own 37-73 ns, CGAL 30-34 ns
// The own filter was never faster, its tighter bound bought nothing
// measurable, and its underflow analysis is one more thing to trust; so the
// predicates call CGAL directly. A faster exact stage (Shewchuk's adaptive
// expansions) is the place to win on near-degenerate input if it matters.
// CGAL stays in this file: nothing in the public headers includes it.

#include <mr/kernel/predicates.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace mr {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

int sign_of(CGAL::Sign s) { return static_cast<int>(s); }  // Orientation and Oriented_side alias Sign

Epick::Point_2 to_cgal(const Vec2d& p) { return {p.x(), p.y()}; }
Epick::Point_3 to_cgal(const Vec3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

int orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  return sign_of(Epick::Orientation_2()(to_cgal(a), to_cgal(b), to_cgal(c)));
}

int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  // A repeated point (a shared corner, as the triangle tests ask often) makes the determinant 0;
  // CGAL's interval filter cannot see that unless the repeat is `a`, and computes it exactly.
  if (a == b || a == c || a == d || b == c || b == d || c == d) return 0;
  return sign_of(Epick::Orientation_3()(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
}

PlaneSideFilter::PlaneSideFilter(const Vec3d& a, const Vec3d& b, const Vec3d& c)
    : a_(a), ab_(b - a), ac_(c - a), largest_(ab_.cwiseAbs().cwiseMax(ac_.cwiseAbs())) {
  minor_ = ab_.x() * ac_.y() - ac_.x() * ab_.y();
}

// CGAL's static filter for Orientation_3 (Static_filters/Orientation_3.h):
// the determinant of the rows b - a, c - a, p - a expanded as CGAL's
// determinant() does, certified when larger than 5.1107127829973299e-15
// times the largest |coordinate difference| per axis multiplied together,
// unless those are small enough to underflow or large enough to overflow.
int PlaneSideFilter::certain_sign(const Vec3d& p) const {
  const Vec3d ap = p - a_;
  const Vec3d largest = largest_.cwiseMax(ap.cwiseAbs());
  const double smallest_axis = largest.minCoeff();
  const double largest_axis = largest.maxCoeff();
  if (smallest_axis < 1e-97 || largest_axis > 1e102) return 0;
  const double m02 = ab_.x() * ap.y() - ap.x() * ab_.y();
  const double m12 = ac_.x() * ap.y() - ap.x() * ac_.y();
  const double det = minor_ * ap.z() - m02 * ac_.z() + m12 * ab_.z();
  const double bound = 5.1107127829973299e-15 * largest.x() * largest.y() * largest.z();
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

bool certainly_apart_but_shared(const PlaneSideFilter& plane, const std::array<Vec3d, 3>& p,
                                const std::array<Vec3d, 3>& q) {
  int side = 0;
  for (const Vec3d& x : q) {
    if (x == p[0] || x == p[1] || x == p[2]) continue;
    const int s = plane.certain_sign(x);
    if (s == 0 || (side != 0 && s != side)) return false;
    side = s;
  }
  return side != 0;
}

int incircle(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d) {
  return sign_of(Epick::Side_of_oriented_circle_2()(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d)));
}

int insphere(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, const Vec3d& e) {
  return sign_of(
      Epick::Side_of_oriented_sphere_3()(to_cgal(a), to_cgal(b), to_cgal(c), to_cgal(d), to_cgal(e)));
}

int orient2d_projected(const Vec3d& a, const Vec3d& b, const Vec3d& c, int axis) {
  const int i = axis == 0 ? 1 : 0;
  const int j = axis == 2 ? 1 : 2;
  return orient2d(Vec2d(a[i], a[j]), Vec2d(b[i], b[j]), Vec2d(c[i], c[j]));
}

}  // namespace mr
