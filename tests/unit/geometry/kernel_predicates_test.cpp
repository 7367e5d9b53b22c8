// Exact predicates: sign conventions, degenerate inputs on which a plain
// double determinant fails, and agreement with an independent GMP reference.

#include <mr/kernel/exact_point.h>
#include <mr/kernel/predicates.h>

#include <gmpxx.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace mr;

namespace {

mpq_class q(double v) { return mpq_class(v); }

int reference_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  const mpq_class m[3][3] = {{q(b.x()) - q(a.x()), q(b.y()) - q(a.y()), q(b.z()) - q(a.z())},
                             {q(c.x()) - q(a.x()), q(c.y()) - q(a.y()), q(c.z()) - q(a.z())},
                             {q(d.x()) - q(a.x()), q(d.y()) - q(a.y()), q(d.z()) - q(a.z())}};
  const mpq_class det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return sgn(det);
}

int reference_orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const mpq_class det =
      (q(b.x()) - q(a.x())) * (q(c.y()) - q(a.y())) - (q(b.y()) - q(a.y())) * (q(c.x()) - q(a.x()));
  return sgn(det);
}

int naive_orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  const double det = (b - a).cross(c - a).dot(d - a);
  return (det > 0) - (det < 0);
}

/// d is the double nearest to a point of the plane through a, b, c: the
/// orientation is decided by the rounding error of d, as small as the
/// rounding errors of a double determinant.
std::array<Vec3d, 4> near_coplanar(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3d offset(unit(rng), unit(rng), unit(rng));
  const Vec3d a = offset + Vec3d(unit(rng), unit(rng), unit(rng));
  const Vec3d b = offset + Vec3d(unit(rng), unit(rng), unit(rng));
  const Vec3d c = offset + Vec3d(unit(rng), unit(rng), unit(rng));
  const double s = unit(rng), t = unit(rng);
  return {a, b, c, a + s * (b - a) + t * (c - a)};
}

}  // namespace

TEST_CASE("orient3d sign convention is positive tet volume", "[kernel]") {
  const Vec3d o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  CHECK(orient3d(o, x, y, z) == 1);
  CHECK(orient3d(o, y, x, z) == -1);
  CHECK(orient3d(o, x, y, Vec3d(0.3, 0.3, 0)) == 0);
  CHECK(orient2d(Vec2d(0, 0), Vec2d(1, 0), Vec2d(0, 1)) == 1);
  CHECK(orient2d(Vec2d(0, 0), Vec2d(0, 1), Vec2d(1, 0)) == -1);
  CHECK(orient2d_projected(o, x, y, 2) == 1);
}

TEST_CASE("orient3d is exact on collinear and coplanar points where doubles fail", "[kernel]") {
  // 0.1, 0.2, 0.3 are not exact in binary, yet these doubles are what they
  // are: the exact answer is whatever GMP says, and ours must agree.
  const Vec3d a(0.1, 0.1, 0.1), b(0.2, 0.2, 0.2), c(0.3, 0.3, 0.3);
  const Vec3d d(0.7, -0.3, 0.11);
  CHECK(orient3d(a, b, c, d) == reference_orient3d(a, b, c, d));

  std::mt19937_64 rng(42);
  int naive_wrong = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto [p, r, s, t] = near_coplanar(rng);
    const int expected = reference_orient3d(p, r, s, t);
    REQUIRE(orient3d(p, r, s, t) == expected);
    REQUIRE(orient3d(r, p, s, t) == -expected);
    REQUIRE(orient3d(t, p, r, s) == -expected);  // odd permutation
    naive_wrong += naive_orient3d(p, r, s, t) != expected;
  }
  // The inputs really are hard: a plain determinant gets many of them wrong.
  CHECK(naive_wrong > 1000);
}

TEST_CASE("orient3d is exact on exactly coplanar points with tiny perturbations", "[kernel]") {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> small(-1000, 1000);
  for (int i = 0; i < 5000; ++i) {
    // Integer points on the plane x + 2y + 3z = 0, scaled by a power of two (exact).
    Vec3d pts[4];
    for (Vec3d& p : pts) {
      const double y = small(rng), z = small(rng);
      p = Vec3d(-2 * y - 3 * z, y, z) * std::ldexp(1.0, -30);
    }
    REQUIRE(orient3d(pts[0], pts[1], pts[2], pts[3]) == 0);
    const int axis = i % 3;
    pts[3][axis] = std::nextafter(pts[3][axis], i % 2 ? 1e9 : -1e9);
    REQUIRE(orient3d(pts[0], pts[1], pts[2], pts[3]) == reference_orient3d(pts[0], pts[1], pts[2], pts[3]));
  }
}

TEST_CASE("orient2d agrees with GMP on Shewchuk's near-collinear grid", "[kernel]") {
  // Shewchuk's classic plot: p = (0.5 + i u, 0.5 + j u) against the line
  // through (12, 12) and (24, 24), u = 2^-53.
  const double u = std::ldexp(1.0, -53);
  const Vec2d b(12, 12), c(24, 24);
  int naive_wrong = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      const Vec2d a(0.5 + i * u, 0.5 + j * u);
      const int expected = reference_orient2d(a, b, c);
      REQUIRE(orient2d(a, b, c) == expected);
      const double naive = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      naive_wrong += ((naive > 0) - (naive < 0)) != expected;
    }
  }
  CHECK(naive_wrong > 0);
}

TEST_CASE("predicates stay exact for huge and tiny magnitudes", "[kernel]") {
  for (double scale : {1e-300, 1e-160, 1e150, 1e300}) {
    const Vec3d a = Vec3d(0, 0, 0) * scale, b = Vec3d(1, 0, 0) * scale, c = Vec3d(0, 1, 0) * scale;
    const Vec3d above = Vec3d(0.25, 0.25, 1e-16) * scale;
    CHECK(orient3d(a, b, c, above) == reference_orient3d(a, b, c, above));
    CHECK(orient3d(a, b, c, above) == 1);
    CHECK(orient3d(a, b, c, Vec3d(0.25, 0.25, 0) * scale) == 0);
  }
  // Mixed magnitudes: the filter must not trust an underflowed product.
  const Vec3d a(0, 0, 0), b(1e90, 0, 0), c(0, 1e-200, 1e-200), d(0, 1e-200, 1.5e-200);
  CHECK(orient3d(a, b, c, d) == reference_orient3d(a, b, c, d));
}

TEST_CASE("the prepared plane filter never contradicts orient3d and decides generic points", "[kernel]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int decided_generic = 0, decided_near = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::array<Vec3d, 4> near = near_coplanar(rng);
    const Vec3d generic(unit(rng), unit(rng), unit(rng));
    const PlaneSideFilter plane(near[0], near[1], near[2]);
    for (const Vec3d& p : {near[3], generic, near[0]}) {
      const int certain = plane.certain_sign(p);
      if (certain != 0) REQUIRE(certain == reference_orient3d(near[0], near[1], near[2], p));
    }
    decided_generic += plane.certain_sign(generic) != 0;
    decided_near += plane.certain_sign(near[3]) != 0;
  }
  CHECK(decided_generic > 19900);  // a random point is near the plane once in thousands
  CHECK(decided_near < 200);       // within rounding of the plane: left to orient3d
  // Magnitudes where the bound itself would underflow or overflow are left to orient3d.
  for (double scale : {1e-300, 1e300}) {
    const PlaneSideFilter plane(Vec3d(0, 0, 0) * scale, Vec3d(1, 0, 0) * scale, Vec3d(0, 1, 0) * scale);
    CHECK(plane.certain_sign(Vec3d(0.25, 0.25, 1) * scale) == 0);
  }
  const PlaneSideFilter plane(Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(0, 1, 0));
  CHECK(plane.certain_sign(Vec3d(0.25, 0.25, 1)) == 1);
  CHECK(plane.certain_sign(Vec3d(0.25, 0.25, -1)) == -1);
  CHECK(plane.certain_sign(Vec3d(0.25, 0.25, 0)) == 0);
  CHECK(plane.certainly_one_side(Vec3d(0, 0, 1), Vec3d(1, 0, 2), Vec3d(0, 1, 3)));
  CHECK(!plane.certainly_one_side(Vec3d(0, 0, 1), Vec3d(1, 0, -2), Vec3d(0, 1, 3)));
  CHECK(!plane.certainly_one_side(Vec3d(0, 0, 1), Vec3d(1, 0, 0), Vec3d(0, 1, 3)));
}

TEST_CASE("insphere and incircle are exact on cospherical points", "[kernel]") {
  // Integer points on the sphere of radius 9 around (0.5, 1024.25, -3),
  // scaled by 2^-10: exactly cospherical in doubles.
  const Vec3d centre(0.5, 1024.25, -3);
  auto on_sphere = [&](double x, double y, double z) {
    return Vec3d((centre + Vec3d(x, y, z)) * std::ldexp(1.0, -10));
  };
  const Vec3d a = on_sphere(9, 0, 0), b = on_sphere(0, 9, 0), c = on_sphere(0, 0, 9);
  const Vec3d d = on_sphere(-1, -4, -8), e = on_sphere(4, -4, 7), f = on_sphere(-8, 1, 4);
  const int orientation = orient3d(a, b, c, d);
  REQUIRE(orientation != 0);
  CHECK(insphere(a, b, c, d, e) == 0);
  CHECK(insphere(a, b, c, d, f) == 0);
  const Vec3d inside = on_sphere(0, 0, 0);
  CHECK(insphere(a, b, c, d, inside) == orientation);
  CHECK(insphere(b, a, c, d, inside) == -orientation);
  Vec3d nudged = e;
  nudged.x() = std::nextafter(e.x(), 0.0);  // a hair towards the centre's x: inside
  CHECK(insphere(a, b, c, d, nudged) == orientation);
  // The rational evaluation agrees on all of these.
  const ExactPoint3 ea(a), eb(b), ec(c), ed(d);
  CHECK(insphere(ea, eb, ec, ed, ExactPoint3(e)) == 0);
  CHECK(insphere(ea, eb, ec, ed, ExactPoint3(inside)) == orientation);
  CHECK(insphere(ea, eb, ec, ed, ExactPoint3(nudged)) == orientation);

  // Circle x^2 + y^2 = 25 through integer points, shifted by 0.125.
  const Vec2d s(0.125, 0.125);
  const Vec2d p0 = s + Vec2d(5, 0), p1 = s + Vec2d(0, 5), p2 = s + Vec2d(-3, -4), p3 = s + Vec2d(4, -3);
  REQUIRE(orient2d(p0, p1, p2) == 1);
  CHECK(incircle(p0, p1, p2, p3) == 0);
  CHECK(incircle(p0, p1, p2, s) == 1);
  CHECK(incircle(p1, p0, p2, s) == -1);
  CHECK(incircle(p0, p1, p2, s + Vec2d(6, 0)) == -1);
}

TEST_CASE("exact points round to the nearest double and evaluate exactly", "[kernel]") {
  const mpq_class third(1, 3);
  CHECK(round_to_nearest(third) == 1.0 / 3.0);
  CHECK(round_to_nearest(mpq_class(-2, 3)) == -2.0 / 3.0);
  // Halfway between 1 and its successor: ties go to the even mantissa (1).
  const double next = std::nextafter(1.0, 2.0);
  CHECK(round_to_nearest((mpq_class(1) + mpq_class(next)) / 2) == 1.0);
  CHECK(round_to_nearest(mpq_class(next) - mpq_class(1, 1) / (mpq_class(1) << 60)) == next);

  const ExactPoint3 a(mpq_class(0), mpq_class(0), mpq_class(0));
  const ExactPoint3 b(mpq_class(1), mpq_class(0), mpq_class(0));
  const ExactPoint3 c(mpq_class(0), mpq_class(1), mpq_class(0));
  const ExactPoint3 on_plane(third, third, mpq_class(0));
  const ExactPoint3 above(third, third, mpq_class(1, 1000000007));
  CHECK(orient3d(a, b, c, on_plane) == 0);
  CHECK(orient3d(a, b, c, above) == 1);
  CHECK(orient3d(b, a, c, above) == -1);
  CHECK_FALSE(is_representable(on_plane));
  CHECK(is_representable(b));
  CHECK(orient2d_projected(a, b, on_plane, 2) == 1);
}
