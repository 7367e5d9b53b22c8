// Exact constructions, hybrid points and rounding without inverting tets.

#include <mr/core/errors.h>
#include <mr/kernel/constructions.h>
#include <mr/kernel/point_box.h>
#include <mr/kernel/rounding.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

using namespace mr;

namespace {

Vec3d random_point(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  return {unit(rng), unit(rng), unit(rng)};
}

/// True when x lies on segment [a, b], checked exactly.
bool on_segment(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& x) {
  for (int axis = 0; axis < 3; ++axis) {
    if (orient2d_projected(a, b, x, axis) != 0) return false;
    const mpq_class& lo = a[axis] < b[axis] ? a[axis] : b[axis];
    const mpq_class& hi = a[axis] < b[axis] ? b[axis] : a[axis];
    if (x[axis] < lo || x[axis] > hi) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("constructed intersection points lie exactly on the plane and the segment", "[kernel]") {
  std::mt19937_64 rng(5);
  int constructed = 0, representable = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3d p = random_point(rng), q = random_point(rng), r = random_point(rng);
    const Vec3d a = random_point(rng), b = random_point(rng);
    const PlaneEdgeSides sides = plane_edge_sides(p, q, r, a, b);
    if (!sides.meets() || sides.in_plane()) {
      CHECK_THROWS_AS(intersect_segment_plane(a, b, p, q, r), UsageError);
      continue;
    }
    const ExactPoint3 x = intersect_segment_plane(a, b, p, q, r);
    ++constructed;
    REQUIRE(orient3d(ExactPoint3(p), ExactPoint3(q), ExactPoint3(r), x) == 0);
    REQUIRE(on_segment(ExactPoint3(a), ExactPoint3(b), x));
    // Hybrid predicates on the constructed point agree with pure rationals.
    const HybridPoint hx = HybridPoint::from_exact(x);
    representable += !hx.is_exact();
    REQUIRE(orient3d(HybridPoint(p), q, r, hx) == 0);
    const Vec3d s = random_point(rng);
    REQUIRE(orient3d(hx, q, r, s) == orient3d(x, ExactPoint3(q), ExactPoint3(r), ExactPoint3(s)));
    REQUIRE(orient3d(a, b, s, hx) == 0);  // collinear with a and b
    const std::optional<ExactPoint3> on_face = intersect_segment_triangle_point(a, b, p, q, r);
    REQUIRE(on_face.has_value() ==
            (intersect_segment_triangle(a, b, p, q, r).kind == SegmentTriangleKind::point));
    if (on_face) REQUIRE(*on_face == x);
  }
  CHECK(constructed > 1000);
  CHECK(representable < constructed);  // most cut points need rationals
}

TEST_CASE("constructions return exact endpoints and vertices on touching cases", "[kernel]") {
  const Vec3d p(0, 0, 0), q(4, 0, 0), r(0, 4, 0);
  const ExactPoint3 endpoint = intersect_segment_plane(Vec3d(1, 1, 0), Vec3d(1, 1, 3), p, q, r);
  CHECK(endpoint == ExactPoint3(Vec3d(1, 1, 0)));
  const auto vertex = intersect_segment_triangle_point(Vec3d(8, -1, -1), Vec3d(0, 1, 1), p, q, r);
  REQUIRE(vertex.has_value());
  CHECK(*vertex == ExactPoint3(q));
  CHECK_FALSE(intersect_segment_triangle_point(Vec3d(-1, 1, 0), Vec3d(5, 1, 0), p, q, r).has_value());
  const ExactPoint3 third = intersect_segment_plane(Vec3d(1, 1, -1), Vec3d(1, 1, 2), p, q, r);
  CHECK(third == ExactPoint3(Vec3d(1, 1, 0)));
  const ExactPoint3 x = intersect_segment_plane(Vec3d(0, 0, -1), Vec3d(3, 3, 2), p, q, r);
  const HybridPoint hx = HybridPoint::from_exact(x);
  CHECK_FALSE(hx.is_exact());  // (1, 1, 0): representable, rational dropped at once
  // A third of the way up: not a double, so the hybrid keeps its rational.
  const ExactPoint3 y = intersect_segment_plane(Vec3d(0, 0, -1), Vec3d(1, 1, 2), p, q, r);
  const HybridPoint hy = HybridPoint::from_exact(y);
  REQUIRE(hy.is_exact());
  CHECK(hy.approx.x() == 1.0 / 3.0);
  CHECK(hy == HybridPoint::from_exact(y));
  CHECK_FALSE(hy == HybridPoint(hy.approx));
}

TEST_CASE("a point moved onto a plane along an axis lies on it exactly, other coordinates kept", "[kernel]") {
  std::mt19937_64 rng(7);
  int moved = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3d p = random_point(rng), q = random_point(rng), r = random_point(rng);
    // A rational start too, as the inserter moves cut points (each end on
    // its side of the plane x + y + z = 1.5).
    const HybridPoint a = HybridPoint::from_exact(intersect_segment_plane(
        Vec3d(random_point(rng) - Vec3d(2, 2, 2)), Vec3d(random_point(rng) + Vec3d(2, 2, 2)),
        Vec3d(1.5, 0, 0), Vec3d(0, 1.5, 0), Vec3d(0, 0, 1.5)));
    for (int axis = 0; axis < 3; ++axis) {
      if (orient2d_projected(HybridPoint(p), HybridPoint(q), HybridPoint(r), axis) == 0) {
        CHECK_THROWS_AS(move_onto_plane_along_axis(a, axis, p, q, r), UsageError);
        continue;
      }
      const ExactPoint3 x = move_onto_plane_along_axis(a, axis, p, q, r);
      ++moved;
      REQUIRE(orient3d(ExactPoint3(p), ExactPoint3(q), ExactPoint3(r), x) == 0);
      for (int other = 0; other < 3; ++other) {
        if (other != axis) REQUIRE(x[other] == a.to_exact()[other]);
      }
    }
  }
  CHECK(moved > 2900);
  const Vec3d p(0, 0, 1), q(1, 0, 1), r(0, 1, 1);
  CHECK(move_onto_plane_along_axis(HybridPoint(Vec3d(0.25, 0.5, -3)), 2, p, q, r) ==
        ExactPoint3(Vec3d(0.25, 0.5, 1)));
  CHECK_THROWS_AS(move_onto_plane_along_axis(HybridPoint(Vec3d(0, 0, 0)), 0, p, q, r), UsageError);
}

TEST_CASE("opposite_face keeps the orientation of the tet for every corner", "[kernel]") {
  std::mt19937_64 rng(11);
  std::vector<Vec3d> pts(4);
  for (int i = 0; i < 200; ++i) {
    for (Vec3d& p : pts) p = random_point(rng);
    const Tet tet = {0, 1, 2, 3};
    const int orientation = orient3d(pts[0], pts[1], pts[2], pts[3]);
    for (int corner = 0; corner < 4; ++corner) {
      const auto face = opposite_face(tet, corner);
      REQUIRE(orient3d(pts[tet[corner]], pts[face[0]], pts[face[1]], pts[face[2]]) == orientation);
    }
  }
  CHECK_THROWS_AS(opposite_face({0, 1, 2, 3}, 4), UsageError);
}

TEST_CASE("try_round accepts when safe and refuses when rounding flattens or flips a sliver", "[kernel]") {
  // x = 1/3 exactly; its nearest double r = fl(1/3) is below 1/3.
  const double r = 1.0 / 3.0;
  const mpq_class third(1, 3);
  const ExactPoint3 x(third, third, third);
  REQUIRE(round_to_nearest(third) == r);

  // Sliver: the opposite face lies in the plane x = r, a hair below the vertex.
  const HybridPoint b(Vec3d(r, 0, 0)), c(Vec3d(r, 1, 0)), d(Vec3d(r, 0, 1));
  const OppositeFace sliver = {&b, &d, &c};
  HybridPoint vertex = HybridPoint::from_exact(x);
  REQUIRE(vertex.is_exact());
  REQUIRE(orient3d(vertex, b, d, c) == 1);  // valid while exact
  CHECK_FALSE(try_round(vertex, std::span(&sliver, 1)));
  CHECK(vertex.is_exact());  // refused: untouched
  CHECK(orient3d(HybridPoint(vertex.approx), b, d, c) == 0);

  // Flip: the face is rational, strictly between the vertex and its rounding.
  const mpq_class delta = mpq_class(1) / (mpq_class(1) << 60);
  const mpq_class between = mpq_class(r) + delta / 2;
  const HybridPoint fb = HybridPoint::from_exact({between, 0, 0});
  const HybridPoint fc = HybridPoint::from_exact({between, 1, 0});
  const HybridPoint fd = HybridPoint::from_exact({between, 0, 1});
  HybridPoint close = HybridPoint::from_exact({mpq_class(r) + delta, third, third});
  REQUIRE(close.approx.x() == r);
  REQUIRE(orient3d(close, fb, fd, fc) == 1);
  REQUIRE(orient3d(HybridPoint(close.approx), fb, fd, fc) == -1);
  const OppositeFace flipping = {&fb, &fd, &fc};
  CHECK_FALSE(try_round(close, std::span(&flipping, 1)));
  CHECK(close.is_exact());

  // A well-shaped neighbourhood: rounding is accepted and the rational dropped.
  const HybridPoint fb2(Vec3d(0, 0, 0)), fc2(Vec3d(0, 1, 0)), fd2(Vec3d(0, 0, 1));
  const OppositeFace faces[2] = {{&fb2, &fd2, &fc2}, {&b, &d, &c}};
  HybridPoint safe = HybridPoint::from_exact(x);
  REQUIRE(orient3d(safe, fb2, fd2, fc2) == 1);
  CHECK_FALSE(try_round(safe, faces));  // the sliver still vetoes
  CHECK(try_round(safe, std::span(faces, 1)));
  CHECK_FALSE(safe.is_exact());
  CHECK(safe.approx == Vec3d(r, r, r));
}

TEST_CASE("try_round_vertex rounds mesh vertices against their incident tets", "[kernel]") {
  const double r = 1.0 / 3.0;
  const mpq_class third(1, 3);
  // Vertex 0 is rational; tet 0 is a sliver against the face x = r, tet 1 is fine.
  std::vector<HybridPoint> positions = {HybridPoint::from_exact({third, third, third}),
                                        Vec3d(r, 0, 0),
                                        Vec3d(r, 1, 0),
                                        Vec3d(r, 0, 1),
                                        Vec3d(0, 0, 0),
                                        Vec3d(0, 1, 0),
                                        Vec3d(0, 0, 1)};
  // Written with vertex 0 at different corners; both positively oriented.
  const Tet sliver = {1, 0, 2, 3};
  const Tet good = {4, 5, 6, 0};
  REQUIRE(orient3d(positions[1], positions[0], positions[2], positions[3]) == 1);
  REQUIRE(orient3d(positions[4], positions[5], positions[6], positions[0]) == 1);
  const std::vector<Tet> both = {sliver, good};
  CHECK_FALSE(try_round_vertex(positions, 0, both));
  CHECK(positions[0].is_exact());
  CHECK(try_round_vertex(positions, 0, std::span(&good, 1)));
  CHECK_FALSE(positions[0].is_exact());
  CHECK(try_round_vertex(positions, 4, std::span(&good, 1)));  // already doubles
  positions[0] = HybridPoint::from_exact({third, third, third});
  const Tet elsewhere = {1, 2, 3, 4};
  CHECK_THROWS_AS(try_round_vertex(positions, 0, std::span(&elsewhere, 1)), UsageError);
  CHECK_THROWS_AS(try_round_vertex(positions, 99, std::span(&good, 1)), UsageError);
}

TEST_CASE("hybrid predicates agree with rationals on random mixed inputs", "[kernel]") {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 2000; ++i) {
    // Rational points near a common plane, so the interval filter is often inconclusive.
    const Vec3d p = random_point(rng), q = random_point(rng), r = random_point(rng);
    HybridPoint pts[4];
    ExactPoint3 exact[4];
    for (int k = 0; k < 4; ++k) {
      std::uniform_int_distribution<int> small(1, 1000);
      const mpq_class s(small(rng), 997), t(small(rng), 1009);
      const ExactPoint3 ep(p), eq(q), er(r);
      exact[k] = {ep.x + s * (eq.x - ep.x) + t * (er.x - ep.x), ep.y + s * (eq.y - ep.y) + t * (er.y - ep.y),
                  ep.z + s * (eq.z - ep.z) + t * (er.z - ep.z)};
      if (k == 3 && i % 2) exact[k].z += mpq_class(1) / (mpq_class(1) << 70);
      if (k == i % 4) exact[k] = ExactPoint3(round_to_nearest(exact[k]));  // a plain double one
      pts[k] = HybridPoint::from_exact(exact[k]);
    }
    REQUIRE(orient3d(pts[0], pts[1], pts[2], pts[3]) == orient3d(exact[0], exact[1], exact[2], exact[3]));
    REQUIRE(orient2d_projected(pts[0], pts[1], pts[2], i % 3) ==
            orient2d_projected(exact[0], exact[1], exact[2], i % 3));
  }
}

TEST_CASE("intersection tests on rational points match the same configuration in doubles", "[kernel]") {
  // Scaling by 1/3 preserves every incidence, but makes the points rational.
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> coord(0, 3);
  auto point = [&] { return Vec3d(coord(rng), coord(rng), coord(rng)); };
  auto third_of = [](const Vec3d& p) {
    const mpq_class third(1, 3);
    return HybridPoint::from_exact({third * p.x(), third * p.y(), third * p.z()});
  };
  int compared = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3d t[3] = {point(), point(), point()};
    Vec3d u[3] = {point(), point(), point()};
    if (i % 2) u[0] = t[1];
    if (orient2d_projected(t[0], t[1], t[2], 0) == 0 && orient2d_projected(t[0], t[1], t[2], 1) == 0 &&
        orient2d_projected(t[0], t[1], t[2], 2) == 0) {
      continue;  // degenerate triangle
    }
    const SegmentTriangleHit d = intersect_segment_triangle(u[0], u[1], t[0], t[1], t[2]);
    const SegmentTriangleHit h = intersect_segment_triangle(third_of(u[0]), third_of(u[1]), third_of(t[0]),
                                                            third_of(t[1]), third_of(t[2]));
    REQUIRE(h.kind == d.kind);
    REQUIRE(h.on_segment == d.on_segment);
    REQUIRE(h.on_triangle == d.on_triangle);
    REQUIRE(h.index == d.index);
    bool u_degenerate = true;
    for (int axis = 0; axis < 3; ++axis) u_degenerate &= orient2d_projected(u[0], u[1], u[2], axis) == 0;
    if (u_degenerate) continue;
    const TriangleTriangleHit dt = intersect_triangles(t[0], t[1], t[2], u[0], u[1], u[2]);
    const TriangleTriangleHit ht = intersect_triangles(third_of(t[0]), third_of(t[1]), third_of(t[2]),
                                                       third_of(u[0]), third_of(u[1]), third_of(u[2]));
    REQUIRE(ht.kind == dt.kind);
    REQUIRE(ht.shared_vertices == dt.shared_vertices);
    ++compared;
  }
  CHECK(compared > 1000);
}

TEST_CASE("point boxes: a segment-plane box contains the exact point, box signs are exact", "[kernel]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random_point = [&] { return Vec3d(unit(rng), unit(rng), unit(rng)); };
  const auto inside = [](const mpq_class& x, double lo, double hi) {
    return mpq_class(lo) <= x && x <= mpq_class(hi);
  };
  int certain = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const HybridPoint p = random_point(), q = random_point(), r = random_point();
    // Crossing segments; every fourth nearly in the plane, where the filter may give up.
    HybridPoint a = random_point(), b = random_point();
    if (orient3d(p, q, r, a) * orient3d(p, q, r, b) >= 0) continue;
    if (trial % 4 == 0) {
      a = HybridPoint::from_exact(intersect_segment_plane(a, b, p, q, r));
      a = HybridPoint(a.approx + 1e-15 * random_point());
      if (orient3d(p, q, r, a) * orient3d(p, q, r, b) >= 0) continue;
    }
    const ExactPoint3 exact = intersect_segment_plane(a, b, p, q, r);
    const std::optional<PointBox> box = box_of_segment_plane(a, b, p, q, r);
    if (!box) continue;
    for (int k = 0; k < 3; ++k) REQUIRE(inside(exact[k], box->lo[k], box->hi[k]));
    // A box sign, when certain, is the exact sign for the point it contains.
    const HybridPoint cut = HybridPoint::from_exact(exact);
    const HybridPoint u = random_point(), v = random_point();
    for (int axis = 0; axis < 3; ++axis) {
      const int sign = orient2d_projected(box_of(u), box_of(v), *box, axis);
      if (sign == kUncertainSign) continue;
      ++certain;
      REQUIRE(sign == orient2d_projected(u, v, cut, axis));
    }
  }
  CHECK(certain > 1000);
  // A box of a rational point holds it; a double's box is the point.
  const HybridPoint third =
      HybridPoint::from_exact(ExactPoint3(mpq_class(1, 3), mpq_class(2, 3), mpq_class(-1, 3)));
  const PointBox box = box_of(third);
  for (int k = 0; k < 3; ++k) CHECK(inside((*third.exact)[k], box.lo[k], box.hi[k]));
  CHECK(box_of(HybridPoint(Vec3d(1, 2, 3))).lo == Vec3d(1, 2, 3));
}

TEST_CASE("exact orientation of rational points matches the rational determinant", "[kernel]") {
  // Points with unrelated denominators per coordinate, and coplanar and
  // collinear ones built by construction: the integer (homogeneous)
  // evaluation must give the sign of the plain mpq determinant.
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> small(-50, 50), positive(1, 97);
  const auto random_rational = [&] { return mpq_class(small(rng), positive(rng)); };
  const auto random_point = [&] {
    return ExactPoint3(random_rational(), random_rational(), random_rational());
  };
  const auto reference3 = [](const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c,
                             const ExactPoint3& d) {
    const mpq_class ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y,
                    vz = c.z - a.z, wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
    return sgn(mpq_class(ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx)));
  };
  int zeros = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const ExactPoint3 a = random_point(), b = random_point(), c = random_point();
    ExactPoint3 d = random_point();
    if (trial % 3 == 0) {  // on the plane of a, b, c
      const mpq_class s = random_rational(), t = random_rational();
      d = ExactPoint3(a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y),
                      a.z + s * (b.z - a.z) + t * (c.z - a.z));
    }
    const int expected = reference3(a, b, c, d);
    zeros += expected == 0;
    REQUIRE(orient3d(a, b, c, d) == expected);
    REQUIRE(orient3d(b, a, c, d) == -expected);
    const ExactPoint3 on_line(a.x + mpq_class(1, 3) * (b.x - a.x), a.y + mpq_class(1, 3) * (b.y - a.y),
                              a.z + mpq_class(1, 3) * (b.z - a.z));
    for (int axis = 0; axis < 3; ++axis) {
      const int i = axis == 0 ? 1 : 0;
      const int j = axis == 2 ? 1 : 2;
      const int expected2 = sgn(mpq_class((b[i] - a[i]) * (d[j] - a[j]) - (b[j] - a[j]) * (d[i] - a[i])));
      REQUIRE(orient2d_projected(a, b, d, axis) == expected2);
      REQUIRE(orient2d_projected(a, b, on_line, axis) == 0);
    }
  }
  CHECK(zeros >= 900);
}

TEST_CASE("bit_size counts the bits of the longest coordinate", "[kernel]") {
  CHECK(bit_size(ExactPoint3(Vec3d(0.5, 3.0, -1.0))) == 3);  // 1/2 and 3/1: two bits and one
  const ExactPoint3 third(mpq_class(1, 3), mpq_class(0), mpq_class(-255, 256));
  CHECK(bit_size(third) == 8 + 9);
  // A cut of a cut is much longer than a cut of doubles.
  const HybridPoint a(Vec3d(0.1, 0.2, 0.3)), b(Vec3d(0.9, 0.7, 0.4));
  const HybridPoint p(Vec3d(0.5, 0, 0)), q(Vec3d(0.45, 1, 0.1)), r(Vec3d(0.55, 0.3, 1));
  const HybridPoint first = HybridPoint::from_exact(intersect_segment_plane(a, b, p, q, r));
  const HybridPoint second = HybridPoint::from_exact(intersect_segment_plane(
      first, HybridPoint(Vec3d(0.2, 0.9, 0.8)), Vec3d(0, 0.4, 0), Vec3d(1, 0.5, 0.1), Vec3d(0.3, 0.45, 1)));
  REQUIRE(first.is_exact());
  REQUIRE(second.is_exact());
  CHECK(bit_size(*second.exact) > 3 * bit_size(*first.exact) / 2);
}
