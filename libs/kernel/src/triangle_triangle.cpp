// Triangle/triangle classification. First the shape of the intersection
// (empty, a point, a segment, or an area) from exact predicates only, then
// the common vertices turn it into shared_vertex / shared_edge.
//
// Non-coplanar triangles meet along the line L where their planes cross; each
// triangle cuts L in a point or a segment, and the ordering of the segment
// ends along L is read from orient3d signs (Guigue and Devillers, "Fast and
// robust triangle-triangle overlap test using orientation predicates", 2003),
// whose equality cases are exactly the touching configurations.

#include "coplanar.h"

#include <mr/kernel/intersections.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <type_traits>
#include <utility>

namespace mr {
namespace {

enum class Shape { empty, point, segment, area };

template <class P>
using Tri = std::array<const P*, 3>;

bool all_same_strict_sign(const std::array<int, 3>& s) {
  return (s[0] > 0 && s[1] > 0 && s[2] > 0) || (s[0] < 0 && s[1] < 0 && s[2] < 0);
}

bool all_zero(const std::array<int, 3>& s) { return s[0] == 0 && s[1] == 0 && s[2] == 0; }

/// Index of the only vertex on the plane when the other two are strictly on
/// one side (the triangle touches the plane at that vertex only), else -1.
int lone_vertex_on_plane(const std::array<int, 3>& s) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (s[i] == 0 && s[j] != 0 && s[j] == s[k]) return i;
  }
  return -1;
}

/// A vertex strictly on one side with both others on the other closed side.
int vertex_alone(const std::array<int, 3>& s) {
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (s[i] != 0 && s[i] * s[j] <= 0 && s[i] * s[k] <= 0) return i;
  }
  return -1;
}

template <class P>
Tri<P> rotated(const Tri<P>& t, int first) {
  return {t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
}

/// Both triangles cut L in a segment of positive length; compare the ends.
template <class P>
Shape overlap_on_line(Tri<P> t1, Tri<P> t2, const std::array<int, 3>& s1on2,
                      const std::array<int, 3>& s2on1) {
  const int i1 = vertex_alone(s1on2);
  const int i2 = vertex_alone(s2on1);
  const bool flip2 = s1on2[i1] < 0;
  const bool flip1 = s2on1[i2] < 0;
  t1 = rotated(t1, i1);
  t2 = rotated(t2, i2);
  // Make p1 lie on the positive side of triangle 2 and p2 on the positive side of triangle 1.
  if (flip2) std::swap(t2[1], t2[2]);
  if (flip1) std::swap(t1[1], t1[2]);
  const P &p1 = *t1[0], &q1 = *t1[1], &r1 = *t1[2];
  const P &p2 = *t2[0], &q2 = *t2[1], &r2 = *t2[2];
  // Each orientation compares one end of one cut with one end of the other
  // along L. The cuts overlap iff both are <= 0 in our orient3d convention
  // (checked against rational constructions in the tests); a zero means
  // they share only an end point.
  const int first = orient3d(p1, q1, p2, q2);
  const int second = orient3d(p1, r1, r2, p2);
  if (first > 0 || second > 0) return Shape::empty;
  if (first == 0 || second == 0) return Shape::point;
  return Shape::segment;
}

template <class P>
Shape non_coplanar_shape(const Tri<P>& t1, const Tri<P>& t2, const std::array<int, 3>& s1on2,
                         const std::array<int, 3>& s2on1) {
  if (const int i = lone_vertex_on_plane(s1on2); i >= 0) {
    const detail::Projection proj = detail::projection_for(*t2[0], *t2[1], *t2[2]);
    return detail::in_triangle(proj, t2.data(), *t1[i]) ? Shape::point : Shape::empty;
  }
  if (const int i = lone_vertex_on_plane(s2on1); i >= 0) {
    const detail::Projection proj = detail::projection_for(*t1[0], *t1[1], *t1[2]);
    return detail::in_triangle(proj, t1.data(), *t2[i]) ? Shape::point : Shape::empty;
  }
  return overlap_on_line(t1, t2, s1on2, s2on1);
}

/// Intersection of segments [a, b] and [c, d], both of positive length and
/// on one line: empty, a point, or a segment. Along a line, every coordinate
/// in which a and b differ orders the points.
template <class P>
Shape collinear_overlap(const P& a, const P& b, const P& c, const P& d) {
  for (int k = 0; k < 3; ++k) {
    if (detail::coordinate(a, k) == detail::coordinate(b, k)) continue;
    auto sorted = [k](const P& u, const P& v) {
      auto cu = detail::coordinate(u, k), cv = detail::coordinate(v, k);
      return cu < cv ? std::pair{cu, cv} : std::pair{cv, cu};
    };
    const auto [lo1, hi1] = sorted(a, b);
    const auto [lo2, hi2] = sorted(c, d);
    const auto& lo = lo1 > lo2 ? lo1 : lo2;
    const auto& hi = hi1 < hi2 ? hi1 : hi2;
    return lo > hi ? Shape::empty : lo == hi ? Shape::point : Shape::segment;
  }
  throw UsageError("exact intersection test: degenerate triangle edge");
}

/// Coplanar triangles: separating-axis test on the edge lines of both. A
/// line weakly separating them carries their common boundary if any.
template <class P>
Shape coplanar_shape(const Tri<P>& t1, const Tri<P>& t2) {
  const detail::Projection proj1 = detail::projection_for(*t1[0], *t1[1], *t1[2]);
  const detail::Projection proj2 = detail::projection_for(*t2[0], *t2[1], *t2[2]);
  bool touching = false;
  Shape contact = Shape::empty;
  const Tri<P>* tris[2] = {&t1, &t2};
  const detail::Projection* projs[2] = {&proj1, &proj2};
  for (int owner = 0; owner < 2; ++owner) {
    const Tri<P>& t = *tris[owner];
    const Tri<P>& other = *tris[1 - owner];
    for (int e = 0; e < 3; ++e) {
      const P& u = *t[e];
      const P& v = *t[(e + 1) % 3];
      std::array<int, 3> s;
      for (int k = 0; k < 3; ++k) s[k] = detail::side(*projs[owner], u, v, *other[k]);
      if (s[0] < 0 && s[1] < 0 && s[2] < 0) return Shape::empty;
      if (s[0] > 0 || s[1] > 0 || s[2] > 0 || touching) continue;
      // The other triangle is on the closed outer side: contact lies on this edge.
      touching = true;
      const int on_line = (s[0] == 0) + (s[1] == 0) + (s[2] == 0);
      if (on_line == 1) {
        contact = Shape::point;
      } else {
        const int k = s[0] != 0 ? 1 : 0;
        const int l = s[2] != 0 ? 1 : 2;
        contact = collinear_overlap(u, v, *other[k], *other[l]);
      }
    }
  }
  return touching ? contact : Shape::area;
}

/// The corners the two triangles have in common (exact equality): how many
/// pairs are equal, and per triangle a bit per corner that has an equal one.
struct CommonCorners {
  int count = 0;
  unsigned in1 = 0, in2 = 0;
};

template <class P>
CommonCorners common_corners(const Tri<P>& t1, const Tri<P>& t2) {
  CommonCorners common;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (*t1[i] == *t2[j]) {
        ++common.count;
        common.in1 |= 1u << i;
        common.in2 |= 1u << j;
      }
  return common;
}

/// Whether the triangles' planes are nearly one, estimated in doubles: there orient3d needs exact
/// arithmetic, and the projected test below is the cheaper way to a verdict. Only an order of
/// evaluation depends on it, never a verdict.
Vec3d normal_of(const Tri<Vec3d>& t) { return (*t[1] - *t[0]).cross(*t[2] - *t[0]); }

/// `n` is t2's normal (normal_of).
bool nearly_coplanar(const Tri<Vec3d>& t1, const Tri<Vec3d>& t2, const Vec3d& n) {
  double length = 0.0;
  for (const Tri<Vec3d>* t : {&t1, &t2})
    for (int i = 0; i < 3; ++i)
      length = std::max(length, (*(*t)[(i + 1) % 3] - *(*t)[i]).cwiseAbs().maxCoeff());
  const double tolerance = 1e-6 * n.cwiseAbs().maxCoeff() * length;
  for (const Vec3d* x : t1)
    if (std::abs(n.dot(*x - *t2[0])) > tolerance) return false;
  return true;
}

/// Whether c and d lie strictly on opposite sides of the line ab seen along some axis. Then
/// triangles abc and abd meet only along ab, in one plane or not: two planes through ab meet in
/// its line, and in one plane the projection keeps sides. On nearly flat neighbours this is
/// well conditioned where orient3d(a, b, c, d) is not (it goes to exact arithmetic).
template <class P>
bool opposite_in_a_projection(const P& a, const P& b, const P& c, const P& d) {
  for (int axis = 2; axis >= 0; --axis) {
    const int side_c = orient2d_projected(a, b, c, axis);
    if (side_c != 0 && orient2d_projected(a, b, d, axis) == -side_c) return true;
  }
  return false;
}

/// Triangles with exactly one common edge (a, b) and third corners c and d
/// meet beyond that edge only when they lie in one plane with c and d on
/// one side of it: one orient3d decides what the general test asks up to
/// six for. Neighbouring faces are most of the pairs a self-intersection
/// check sees, and on flat regions every one of those tests goes to exact
/// arithmetic. False where a triangle is degenerate: the general test decides.
template <class P>
bool classify_on_common_edge(const Tri<P>& t1, const Tri<P>& t2, const CommonCorners& common,
                             TriangleTriangleHit& hit) {
  if (common.count != 2 || std::popcount(common.in1) != 2 || std::popcount(common.in2) != 2) return false;
  const int c = std::countr_zero(~common.in1 & 7u);  // the corners off the edge
  const int d = std::countr_zero(~common.in2 & 7u);
  const P& a = *t1[(c + 1) % 3];
  const P& b = *t1[(c + 2) % 3];
  if constexpr (std::is_same_v<P, Vec3d>) {
    // Far from one plane, orient3d decides at once (its filter does).
    if (!nearly_coplanar(t1, t2, normal_of(t2)) && orient3d(a, b, *t1[c], *t2[d]) != 0) {
      hit.kind = TriangleTriangleKind::shared_edge;
      return true;
    }
  }
  if (opposite_in_a_projection(a, b, *t1[c], *t2[d])) {
    hit.kind = TriangleTriangleKind::shared_edge;
    return true;
  }
  if (orient3d(a, b, *t1[c], *t2[d]) != 0) {
    hit.kind = TriangleTriangleKind::shared_edge;
    return true;
  }
  for (int axis = 2; axis >= 0; --axis) {
    const int side_c = orient2d_projected(a, b, *t1[c], axis);
    if (side_c == 0) continue;
    const int side_d = orient2d_projected(a, b, *t2[d], axis);
    if (side_d == 0) return false;
    hit.kind = side_c == side_d ? TriangleTriangleKind::coplanar_overlap : TriangleTriangleKind::shared_edge;
    return true;
  }
  return false;
}

/// Seen along `axis`, an edge line of `a` has every vertex of `b` strictly on the side away from
/// `a`, except a vertex both share on that edge. No common vertex: the projections are apart, so
/// the triangles are (kind disjoint). One common vertex v on that edge, both projections
/// non-degenerate: the projections meet only in v, and a non-degenerate projection is one to
/// one, so the triangles meet only in v (shared_vertex).
bool apart_along_edge_line(const Tri<Vec3d>& a, const Tri<Vec3d>& b, int axis, int shared) {
  for (int e = 0; e < 3; ++e) {
    const Vec3d &u = *a[e], &w = *a[(e + 1) % 3];
    const int inside = orient2d_projected(u, w, *a[(e + 2) % 3], axis);
    if (inside == 0) return false;  // a seen edge-on: no edge line separates
    int on_line = 0;
    bool apart = true;
    for (const Vec3d* y : b) {
      if (shared > 0 && (*y == u || *y == w)) {
        ++on_line;
        continue;
      }
      if (orient2d_projected(u, w, *y, axis) != -inside) {
        apart = false;
        break;
      }
    }
    if (apart && on_line == shared) return true;
  }
  return false;
}

/// The projected test for nearly coplanar triangles with at most one common vertex, along the
/// dominant axis of t2's normal `n2`; false when it does not decide.
bool apart_in_projection(const Tri<Vec3d>& t1, const Tri<Vec3d>& t2, const Vec3d& n2, int shared) {
  const int axis = dominant_axis(n2);
  if (shared == 1 && (orient2d_projected(*t1[0], *t1[1], *t1[2], axis) == 0 ||
                      orient2d_projected(*t2[0], *t2[1], *t2[2], axis) == 0))
    return false;
  return apart_along_edge_line(t1, t2, axis, shared) || apart_along_edge_line(t2, t1, axis, shared);
}

template <class P>
TriangleTriangleHit triangles_impl(const P& p1, const P& q1, const P& r1, const P& p2, const P& q2,
                                   const P& r2) {
  const Tri<P> t1 = {&p1, &q1, &r1}, t2 = {&p2, &q2, &r2};
  const CommonCorners common = common_corners(t1, t2);
  TriangleTriangleHit hit;
  hit.shared_vertices = common.count;
  if (classify_on_common_edge(t1, t2, common, hit)) return hit;
  if constexpr (std::is_same_v<P, Vec3d>) {
    if (common.count <= 1) {
      const Vec3d n2 = normal_of(t2);
      if (nearly_coplanar(t1, t2, n2) && apart_in_projection(t1, t2, n2, common.count)) {
        hit.kind = common.count == 0 ? TriangleTriangleKind::disjoint : TriangleTriangleKind::shared_vertex;
        return hit;
      }
    }
  }
  const std::array<int, 3> s1on2 = {orient3d(p2, q2, r2, p1), orient3d(p2, q2, r2, q1),
                                    orient3d(p2, q2, r2, r1)};
  if (all_same_strict_sign(s1on2)) return hit;
  const std::array<int, 3> s2on1 = {orient3d(p1, q1, r1, p2), orient3d(p1, q1, r1, q2),
                                    orient3d(p1, q1, r1, r2)};
  if (all_same_strict_sign(s2on1)) return hit;
  const bool coplanar = all_zero(s1on2) || all_zero(s2on1);
  // A degenerate triangle makes all its own plane tests zero; in that case
  // the projection chosen below throws.
  const Shape shape = coplanar ? coplanar_shape(t1, t2) : non_coplanar_shape(t1, t2, s1on2, s2on1);
  using K = TriangleTriangleKind;
  switch (shape) {
    case Shape::empty:
      hit.kind = K::disjoint;
      break;
    case Shape::point:
      hit.kind = hit.shared_vertices > 0 ? K::shared_vertex : K::touching;
      break;
    case Shape::segment:
      hit.kind = hit.shared_vertices == 2 ? K::shared_edge : coplanar ? K::coplanar_overlap : K::crossing;
      break;
    case Shape::area:
      hit.kind = K::coplanar_overlap;
      break;
  }
  return hit;
}

}  // namespace

TriangleTriangleHit intersect_triangles(const Vec3d& p1, const Vec3d& q1, const Vec3d& r1, const Vec3d& p2,
                                        const Vec3d& q2, const Vec3d& r2) {
  return triangles_impl(p1, q1, r1, p2, q2, r2);
}

TriangleTriangleHit intersect_triangles(const HybridPoint& p1, const HybridPoint& q1, const HybridPoint& r1,
                                        const HybridPoint& p2, const HybridPoint& q2, const HybridPoint& r2) {
  return triangles_impl(p1, q1, r1, p2, q2, r2);
}

}  // namespace mr
