// Exact intersection tests: the named degenerate configurations, then
// thousands of random small-integer configurations (full of coplanar,
// collinear and touching cases) against an independent GMP construction.

#include <mr/core/errors.h>
#include <mr/kernel/intersections.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

using namespace mr;
using Kind = SegmentTriangleKind;
using TT = TriangleTriangleKind;

namespace {

const Vec3d P(0, 0, 0), Q(4, 0, 0), R(0, 4, 0);  // triangle in z = 0

SegmentTriangleHit seg(const Vec3d& a, const Vec3d& b) { return intersect_segment_triangle(a, b, P, Q, R); }

TT tri(const Vec3d& a, const Vec3d& b, const Vec3d& c) { return intersect_triangles(P, Q, R, a, b, c).kind; }

}  // namespace

TEST_CASE("plane/edge sides classify crossing, touching and in-plane edges", "[kernel]") {
  const PlaneEdgeSides crossing = plane_edge_sides(P, Q, R, Vec3d(1, 1, -1), Vec3d(1, 1, 1));
  CHECK(crossing.source == -1);
  CHECK(crossing.target == 1);
  CHECK(crossing.crosses());
  const PlaneEdgeSides touching = plane_edge_sides(P, Q, R, Vec3d(9, 9, 0), Vec3d(1, 1, 1));
  CHECK_FALSE(touching.crosses());
  CHECK(touching.meets());
  CHECK_FALSE(touching.in_plane());
  CHECK(plane_edge_sides(P, Q, R, Vec3d(9, 9, 0), Vec3d(-5, 1, 0)).in_plane());
  CHECK_FALSE(plane_edge_sides(P, Q, R, Vec3d(0, 0, 1), Vec3d(5, 5, 2)).meets());
}

TEST_CASE("segment/triangle classifies every way a segment can meet a triangle", "[kernel]") {
  SegmentTriangleHit hit = seg(Vec3d(1, 1, -1), Vec3d(1, 1, 1));
  CHECK(hit.proper());

  hit = seg(Vec3d(2, 0, -1), Vec3d(2, 0, 1));  // through the interior of edge 0 (PQ)
  CHECK(hit.kind == Kind::point);
  CHECK(hit.on_triangle == TrianglePart::edge);
  CHECK(hit.index == 0);
  CHECK(seg(Vec3d(2, 2, -1), Vec3d(2, 2, 1)).index == 1);  // edge QR
  CHECK(seg(Vec3d(0, 3, -1), Vec3d(0, 3, 2)).index == 2);  // edge RP

  hit = seg(Vec3d(4, 0, -1), Vec3d(4, 0, 3));  // through vertex Q
  CHECK(hit.on_triangle == TrianglePart::vertex);
  CHECK(hit.index == 1);
  CHECK(seg(Vec3d(-1, -1, -1), Vec3d(1, 1, 1)).index == 0);  // oblique, through P
  CHECK(seg(Vec3d(0, 4, 5), Vec3d(0, 4, -5)).index == 2);

  hit = seg(Vec3d(1, 1, 0), Vec3d(1, 1, 7));  // endpoint on the face
  CHECK(hit.kind == Kind::point);
  CHECK(hit.on_segment == SegmentPart::source);
  CHECK(hit.on_triangle == TrianglePart::interior);
  hit = seg(Vec3d(1, 1, 7), Vec3d(4, 0, 0));  // endpoint on a vertex
  CHECK(hit.on_segment == SegmentPart::target);
  CHECK(hit.on_triangle == TrianglePart::vertex);
  CHECK(hit.index == 1);

  CHECK(seg(Vec3d(5, 5, -1), Vec3d(5, 5, 1)).kind == Kind::none);   // pierces the plane outside
  CHECK(seg(Vec3d(1, 1, 0.5), Vec3d(1, 1, 1)).kind == Kind::none);  // stops short
  hit = seg(Vec3d(-1, 1, 1), Vec3d(5, 1, 1));                       // parallel, disjoint
  CHECK(hit.kind == Kind::none);
  CHECK_FALSE(hit.in_plane);

  hit = seg(Vec3d(-1, 1, 0), Vec3d(5, 1, 0));  // coplanar, overlapping
  CHECK(hit.kind == Kind::coplanar);
  CHECK(hit.in_plane);
  CHECK(seg(Vec3d(1, 1, 0), Vec3d(2, 1, 0)).kind == Kind::coplanar);    // inside the face
  CHECK(seg(Vec3d(-2, 6, 0), Vec3d(6, -2, 0)).kind == Kind::coplanar);  // along edge QR's line
  CHECK(seg(Vec3d(4, 0, 0), Vec3d(9, -3, 0)).kind == Kind::coplanar);   // touching vertex Q
  hit = seg(Vec3d(3, 3, 0), Vec3d(9, 1, 0));                            // coplanar, disjoint
  CHECK(hit.kind == Kind::none);
  CHECK(hit.in_plane);
  CHECK(seg(Vec3d(1, 1, 0), Vec3d(1, 1, 0)).kind == Kind::coplanar);  // a point segment
  CHECK(seg(Vec3d(9, 9, 0), Vec3d(9, 9, 0)).kind == Kind::none);

  CHECK_THROWS_AS(intersect_segment_triangle(Vec3d(0, 0, -1), Vec3d(0, 0, 1), P, Q, Vec3d(8, 0, 0)),
                  UsageError);
}

TEST_CASE("triangle/triangle tells shared features from real intersections", "[kernel]") {
  CHECK(tri(Vec3d(4, 0, 0), Vec3d(0, 4, 0), Vec3d(1, 1, 5)) == TT::shared_edge);       // hinge
  CHECK(tri(Vec3d(4, 0, 0), Vec3d(0, 4, 0), Vec3d(4, 4, 0)) == TT::shared_edge);       // flat neighbour
  CHECK(tri(Vec3d(4, 0, 0), Vec3d(0, 4, 0), Vec3d(1, 1, 0)) == TT::coplanar_overlap);  // folded
  CHECK(tri(Vec3d(0, 0, 0), Vec3d(-3, 1, 2), Vec3d(-1, -3, 1)) == TT::shared_vertex);
  CHECK(tri(Vec3d(0, 0, 0), Vec3d(-3, 0, 0), Vec3d(0, -3, 0)) == TT::shared_vertex);   // coplanar
  CHECK(tri(Vec3d(0, 0, 0), Vec3d(3, 1, 0), Vec3d(1, 3, 0)) == TT::coplanar_overlap);  // nested at a vertex
  CHECK(tri(Vec3d(0, 0, 0), Vec3d(1, 1, -1), Vec3d(1, 1, 1)) == TT::crossing);  // shared vertex + crossing
  CHECK(tri(Vec3d(1, 1, -1), Vec3d(1, 1, 1), Vec3d(9, 9, 0)) == TT::crossing);
  CHECK(tri(Vec3d(1, 1, 0), Vec3d(5, 5, 1), Vec3d(5, 6, 2)) == TT::touching);     // vertex on the face
  CHECK(tri(Vec3d(2, 0, 0), Vec3d(5, -1, 1), Vec3d(5, -1, -1)) == TT::touching);  // vertex on an edge
  CHECK(tri(Vec3d(4, 0, 0) + Vec3d(1, 0, 0), Vec3d(9, 0, 0), Vec3d(5, -3, 0)) == TT::disjoint);
  CHECK(tri(Vec3d(1, 1, 1), Vec3d(2, 1, 1), Vec3d(1, 2, 1)) == TT::disjoint);  // parallel
  CHECK(tri(Vec3d(1, 1, 0), Vec3d(6, 1, 0), Vec3d(1, 6, 0)) == TT::coplanar_overlap);
  CHECK(tri(P, Q, R) == TT::coplanar_overlap);  // identical
  CHECK(tri(Vec3d(4, 0, 0), Vec3d(8, 0, 0), Vec3d(6, -3, 0)) == TT::shared_vertex);
  CHECK(tri(Vec3d(2, 0, 0), Vec3d(6, 0, 0), Vec3d(4, -3, 0)) == TT::coplanar_overlap);  // edge overlap
  CHECK(tri(Vec3d(2, 2, 0), Vec3d(5, 2, 0), Vec3d(5, 0, 0)) == TT::touching);  // coplanar, vertex on edge

  const TriangleTriangleHit hinge = intersect_triangles(P, Q, R, Q, R, Vec3d(1, 1, 5));
  CHECK(hinge.shared_vertices == 2);
  CHECK_FALSE(hinge.improper());
  CHECK(intersect_triangles(P, Q, R, Vec3d(1, 1, -1), Vec3d(1, 1, 1), Vec3d(9, 9, 0)).improper());
}

// ---------------------------------------------------------------------------
// Independent reference: explicit rational constructions (no predicates).

namespace {

using QPoint = std::array<mpq_class, 3>;

QPoint to_q(const Vec3d& p) { return {mpq_class(p.x()), mpq_class(p.y()), mpq_class(p.z())}; }
QPoint sub(const QPoint& a, const QPoint& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
QPoint cross(const QPoint& a, const QPoint& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
mpq_class dot(const QPoint& a, const QPoint& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
QPoint lerp(const QPoint& a, const QPoint& b, const mpq_class& t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}
bool is_zero(const QPoint& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }

enum class Shape { empty, point, segment, area };

/// Clips polygon `poly` (points of the plane with normal n) by the closed
/// inner half-planes of triangle t.
std::vector<QPoint> clip_by_triangle(std::vector<QPoint> poly, const std::array<QPoint, 3>& t,
                                     const QPoint& n) {
  for (int e = 0; e < 3 && !poly.empty(); ++e) {
    const QPoint inward = cross(n, sub(t[(e + 1) % 3], t[e]));
    auto f = [&](const QPoint& x) { return dot(inward, sub(x, t[e])); };
    std::vector<QPoint> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const QPoint& a = poly[i];
      const QPoint& b = poly[(i + 1) % poly.size()];
      const mpq_class fa = f(a), fb = f(b);
      if (fa >= 0) out.push_back(a);
      if ((fa > 0 && fb < 0) || (fa < 0 && fb > 0)) out.push_back(lerp(a, b, fa / (fa - fb)));
    }
    poly = std::move(out);
  }
  return poly;
}

Shape shape_of(const std::vector<QPoint>& pts) {
  if (pts.empty()) return Shape::empty;
  std::size_t far = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (!is_zero(sub(pts[i], pts[0]))) far = i;
  }
  if (far == 0) return Shape::point;
  for (const QPoint& p : pts) {
    if (!is_zero(cross(sub(pts[far], pts[0]), sub(p, pts[0])))) return Shape::area;
  }
  return Shape::segment;
}

std::vector<mpq_class> cut_with_plane(const std::array<QPoint, 3>& t, const QPoint& n, const QPoint& origin,
                                      const QPoint& direction) {
  std::vector<mpq_class> along;
  for (int i = 0; i < 3; ++i) {
    const QPoint& a = t[i];
    const QPoint& b = t[(i + 1) % 3];
    const mpq_class fa = dot(n, sub(a, origin)), fb = dot(n, sub(b, origin));
    if (fa == 0) along.push_back(dot(direction, a));
    if ((fa > 0 && fb < 0) || (fa < 0 && fb > 0)) along.push_back(dot(direction, lerp(a, b, fa / (fa - fb))));
  }
  return along;
}

Shape reference_shape(const std::array<QPoint, 3>& t1, const std::array<QPoint, 3>& t2) {
  const QPoint n1 = cross(sub(t1[1], t1[0]), sub(t1[2], t1[0]));
  const QPoint n2 = cross(sub(t2[1], t2[0]), sub(t2[2], t2[0]));
  const QPoint d = cross(n1, n2);
  if (is_zero(d)) {
    if (dot(n1, sub(t2[0], t1[0])) != 0) return Shape::empty;  // parallel planes
    return shape_of(clip_by_triangle({t1[0], t1[1], t1[2]}, t2, n2));
  }
  const std::vector<mpq_class> s1 = cut_with_plane(t1, n2, t2[0], d);
  const std::vector<mpq_class> s2 = cut_with_plane(t2, n1, t1[0], d);
  if (s1.empty() || s2.empty()) return Shape::empty;
  const mpq_class lo =
      std::max(*std::min_element(s1.begin(), s1.end()), *std::min_element(s2.begin(), s2.end()));
  const mpq_class hi =
      std::min(*std::max_element(s1.begin(), s1.end()), *std::max_element(s2.begin(), s2.end()));
  return lo > hi ? Shape::empty : lo == hi ? Shape::point : Shape::segment;
}

TT reference_kind(const std::array<Vec3d, 3>& a, const std::array<Vec3d, 3>& b) {
  const std::array<QPoint, 3> t1 = {to_q(a[0]), to_q(a[1]), to_q(a[2])};
  const std::array<QPoint, 3> t2 = {to_q(b[0]), to_q(b[1]), to_q(b[2])};
  int shared = 0;
  for (const Vec3d& u : a) {
    for (const Vec3d& v : b) shared += u == v;
  }
  const bool coplanar = is_zero(cross(cross(sub(t1[1], t1[0]), sub(t1[2], t1[0])),
                                      cross(sub(t2[1], t2[0]), sub(t2[2], t2[0])))) &&
                        dot(cross(sub(t1[1], t1[0]), sub(t1[2], t1[0])), sub(t2[0], t1[0])) == 0;
  switch (reference_shape(t1, t2)) {
    case Shape::empty:
      return TT::disjoint;
    case Shape::point:
      return shared > 0 ? TT::shared_vertex : TT::touching;
    case Shape::segment:
      return shared == 2 ? TT::shared_edge : coplanar ? TT::coplanar_overlap : TT::crossing;
    case Shape::area:
      return TT::coplanar_overlap;
  }
  return TT::disjoint;
}

bool degenerate(const std::array<Vec3d, 3>& t) {
  return is_zero(cross(sub(to_q(t[1]), to_q(t[0])), sub(to_q(t[2]), to_q(t[0]))));
}

std::array<Vec3d, 3> random_triangle(std::mt19937_64& rng, int range) {
  std::uniform_int_distribution<int> coord(0, range);
  std::array<Vec3d, 3> t;
  do {
    for (Vec3d& p : t) p = Vec3d(coord(rng), coord(rng), coord(rng));
  } while (degenerate(t));
  return t;
}

}  // namespace

TEST_CASE("triangle/triangle agrees with rational constructions on random degenerate input", "[kernel]") {
  std::mt19937_64 rng(2024);
  std::map<TT, int> seen;
  for (int i = 0; i < 20000; ++i) {
    const int range = i % 2 ? 2 : 3;
    const auto a = random_triangle(rng, range);
    auto b = random_triangle(rng, range);
    if (i % 3 == 0) b[0] = a[i % 9 / 3];  // force shared vertices often
    if (i % 6 == 0) b[1] = a[(i / 6) % 3];
    if (degenerate(b)) continue;
    const TT expected = reference_kind(a, b);
    INFO("case " << i);
    REQUIRE(intersect_triangles(a[0], a[1], a[2], b[0], b[1], b[2]).kind == expected);
    REQUIRE(intersect_triangles(b[2], b[0], b[1], a[1], a[0], a[2]).kind == expected);
    ++seen[expected];
  }
  for (TT kind :
       {TT::disjoint, TT::shared_vertex, TT::shared_edge, TT::touching, TT::crossing, TT::coplanar_overlap}) {
    CHECK(seen[kind] > 50);
  }
}

TEST_CASE("triangle/triangle agrees with rational constructions on nearly coplanar neighbours", "[kernel]") {
  // Corners on a small grid in a tilted plane, each lifted off it by a few units of 2^-40: the
  // orient3d signs need exact arithmetic, the projections along the plane's normal do not.
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coord(0, 4), lift(-2, 2);
  const auto corner = [&] {
    const double x = coord(rng), y = coord(rng);
    return Vec3d(x, y, 0.25 * x + 0.5 * y + std::ldexp(lift(rng), -40));
  };
  std::map<TT, int> seen;
  for (int i = 0; i < 20000; ++i) {
    std::array<Vec3d, 3> a{corner(), corner(), corner()}, b{corner(), corner(), corner()};
    if (i % 2 == 0) b[0] = a[i % 3];  // one common vertex, sometimes two
    if (i % 10 == 0) b[1] = a[(i + 1) % 3];
    if (degenerate(a) || degenerate(b)) continue;
    const TT expected = reference_kind(a, b);
    INFO("case " << i);
    REQUIRE(intersect_triangles(a[0], a[1], a[2], b[0], b[1], b[2]).kind == expected);
    REQUIRE(intersect_triangles(b[1], b[2], b[0], a[2], a[0], a[1]).kind == expected);
    ++seen[expected];
  }
  for (TT kind : {TT::disjoint, TT::shared_vertex, TT::shared_edge, TT::crossing, TT::coplanar_overlap})
    CHECK(seen[kind] > 50);
}

namespace {

/// Reference segment/triangle classification by explicit construction.
SegmentTriangleHit reference_segment_triangle(const Vec3d& a, const Vec3d& b, const std::array<Vec3d, 3>& t) {
  const std::array<QPoint, 3> tq = {to_q(t[0]), to_q(t[1]), to_q(t[2])};
  const QPoint qa = to_q(a), qb = to_q(b);
  const QPoint n = cross(sub(tq[1], tq[0]), sub(tq[2], tq[0]));
  const mpq_class fa = dot(n, sub(qa, tq[0])), fb = dot(n, sub(qb, tq[0]));
  SegmentTriangleHit hit;
  if ((fa > 0 && fb > 0) || (fa < 0 && fb < 0)) return hit;
  if (fa == 0 && fb == 0) {
    hit.in_plane = true;
    if (!clip_by_triangle({qa, qb}, tq, n).empty()) hit.kind = Kind::coplanar;
    return hit;
  }
  const mpq_class s = fa / (fa - fb);
  const QPoint x = lerp(qa, qb, s);
  int zeros = 0, negative = 0;
  std::array<int, 3> edge_sign{};
  for (int e = 0; e < 3; ++e) {
    edge_sign[e] = sgn(dot(cross(sub(tq[(e + 1) % 3], tq[e]), sub(x, tq[e])), n));
    zeros += edge_sign[e] == 0;
    negative += edge_sign[e] < 0;
  }
  if (negative > 0) return hit;
  hit.kind = Kind::point;
  hit.on_segment = s == 0 ? SegmentPart::source : s == 1 ? SegmentPart::target : SegmentPart::interior;
  if (zeros == 1) {
    hit.on_triangle = TrianglePart::edge;
    hit.index = edge_sign[0] == 0 ? 0 : edge_sign[1] == 0 ? 1 : 2;
  } else if (zeros == 2) {
    hit.on_triangle = TrianglePart::vertex;
    for (int v = 0; v < 3; ++v) {
      if (to_q(t[v]) == x) hit.index = v;
    }
  }
  return hit;
}

}  // namespace

TEST_CASE("segment/triangle agrees with rational constructions on random degenerate input", "[kernel]") {
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<int> coord(0, 3);
  std::map<int, int> seen;  // kind * 10 + triangle part
  for (int i = 0; i < 20000; ++i) {
    const auto t = random_triangle(rng, 3);
    const Vec3d a(coord(rng), coord(rng), coord(rng));
    const Vec3d b = i % 4 == 0 ? t[i % 3] * 2 - a : Vec3d(coord(rng), coord(rng), coord(rng));
    const SegmentTriangleHit expected = reference_segment_triangle(a, b, t);
    const SegmentTriangleHit got = intersect_segment_triangle(a, b, t[0], t[1], t[2]);
    INFO("case " << i);
    REQUIRE(got.kind == expected.kind);
    REQUIRE(got.in_plane == expected.in_plane);
    if (expected.kind == Kind::point) {
      REQUIRE(got.on_segment == expected.on_segment);
      REQUIRE(got.on_triangle == expected.on_triangle);
      REQUIRE(got.index == expected.index);
    }
    ++seen[static_cast<int>(expected.kind) * 10 + static_cast<int>(expected.on_triangle)];
  }
  CHECK(seen.size() >= 5);
}
