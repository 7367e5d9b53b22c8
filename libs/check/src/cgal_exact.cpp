// The checks' only CGAL translation unit: exact predicates on doubles from
// the filtered Epick kernel, and the exact self-intersection count.

#include "exact.h"
#include "welded.h"

#include <mr/check/self_intersections.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mpzf.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace mr::check {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Segment = K::Segment_3;
using CgalTriangle = K::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

Point to_point(const Vec3d& p) { return {p.x(), p.y(), p.z()}; }

struct Face {
  Triangle v;  // welded indices
  CgalTriangle t;
};

// Local indices of the vertices a and b share, as pairs (shared_a[k], shared_b[k]).
int shared_vertices(const Triangle& a, const Triangle& b, int shared_a[3], int shared_b[3]) {
  int count = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        shared_a[count] = i;
        shared_b[count] = j;
        ++count;
      }
  return count;
}

int third(int i, int j) { return 3 - i - j; }

// Faces sharing exactly one vertex v meet elsewhere iff the edge opposite v in
// one crosses the other face, or (coplanar) an edge from v enters the other's angle.
bool meet_beyond_vertex(const Face& f, const Face& g, int fi, int gi, const std::vector<Point>& p) {
  const Point& v = p[f.v[fi]];
  const Point &f1 = p[f.v[(fi + 1) % 3]], &f2 = p[f.v[(fi + 2) % 3]];
  const Point &g1 = p[g.v[(gi + 1) % 3]], &g2 = p[g.v[(gi + 2) % 3]];
  if (CGAL::do_intersect(Segment(f1, f2), g.t) || CGAL::do_intersect(Segment(g1, g2), f.t)) return true;
  if (!CGAL::coplanar(v, f1, f2, g1) || !CGAL::coplanar(v, f1, f2, g2)) return false;
  auto ray_inside_angle = [&](const Point& apex_a, const Point& apex_b, const Point& q) {
    // q strictly inside the angle (apex_a, v, apex_b), or on one of its rays.
    const auto side_a = CGAL::coplanar_orientation(v, apex_a, apex_b, q);
    const auto side_b = CGAL::coplanar_orientation(v, apex_b, apex_a, q);
    if (side_a == CGAL::POSITIVE && side_b == CGAL::POSITIVE) return true;
    auto on_ray = [&](const Point& apex) {
      return CGAL::collinear(v, apex, q) && CGAL::compare_xyz(v, apex) == CGAL::compare_xyz(v, q);
    };
    return on_ray(apex_a) || on_ray(apex_b);
  };
  return ray_inside_angle(f1, f2, g1) || ray_inside_angle(f1, f2, g2) || ray_inside_angle(g1, g2, f1) ||
         ray_inside_angle(g1, g2, f2);
}

// Faces sharing an edge meet elsewhere iff they are coplanar and fold onto each other.
bool meet_beyond_edge(const Face& f, const Face& g, const int sf[2], const int sg[2],
                      const std::vector<Point>& p) {
  const Point& u = p[f.v[sf[0]]];
  const Point& w = p[f.v[sf[1]]];
  const Point& a = p[f.v[third(sf[0], sf[1])]];
  const Point& b = p[g.v[third(sg[0], sg[1])]];
  return CGAL::coplanar(u, w, a, b) && CGAL::coplanar_orientation(u, w, a, b) == CGAL::POSITIVE;
}

bool faces_intersect(const Face& f, const Face& g, const std::vector<Point>& p) {
  int sf[3], sg[3];
  switch (shared_vertices(f.v, g.v, sf, sg)) {
    case 0:
      return CGAL::do_intersect(f.t, g.t);
    case 1:
      return meet_beyond_vertex(f, g, sf[0], sg[0], p);
    case 2:
      return meet_beyond_edge(f, g, sf, sg, p);
    default:
      return true;  // the same three vertices: a duplicate
  }
}

}  // namespace

namespace detail {

bool exactly_collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return CGAL::collinear(to_point(a), to_point(b), to_point(c));
}

int orient3d_sign(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  // CGAL's orientation(p,q,r,s) is the sign of det[q-p, r-p, s-p], the same
  // convention as ours.
  return static_cast<int>(CGAL::orientation(to_point(a), to_point(b), to_point(c), to_point(d)));
}

namespace {

// x rounded to a double of the same sign (to_double may flush a tiny value to zero).
double rounded_keeping_sign(const CGAL::Mpzf& x) {
  const int sign = CGAL::sign(x);
  const double rounded = CGAL::to_double(x);
  if (sign != 0 && (rounded == 0.0 || (rounded > 0) != (sign > 0)))
    return sign * std::numeric_limits<double>::min();
  return rounded;
}

}  // namespace

double exact_orient3d_value(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  const auto m = [](double x) { return CGAL::Mpzf(x); };
  const CGAL::Mpzf ux = m(b.x()) - m(a.x()), uy = m(b.y()) - m(a.y()), uz = m(b.z()) - m(a.z());
  const CGAL::Mpzf vx = m(c.x()) - m(a.x()), vy = m(c.y()) - m(a.y()), vz = m(c.z()) - m(a.z());
  const CGAL::Mpzf wx = m(d.x()) - m(a.x()), wy = m(d.y()) - m(a.y()), wz = m(d.z()) - m(a.z());
  return rounded_keeping_sign(wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx));
}

double exact_six_volume(const std::vector<Vec3d>& positions, const std::vector<Triangle>& triangles) {
  CGAL::Mpzf sum(0);
  for (const Triangle& t : triangles) {
    const Vec3d &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    const auto m = [](double x) { return CGAL::Mpzf(x); };
    // a . (b x c), every product exact
    sum = sum + m(a.x()) * (m(b.y()) * m(c.z()) - m(b.z()) * m(c.y())) +
          m(a.y()) * (m(b.z()) * m(c.x()) - m(b.x()) * m(c.z())) +
          m(a.z()) * (m(b.x()) * m(c.y()) - m(b.y()) * m(c.x()));
  }
  return rounded_keeping_sign(sum);
}

}  // namespace detail

std::int64_t count_self_intersections(const TriangleSoup& soup) {
  const detail::Welded welded = detail::weld_identical(soup);
  std::vector<Point> points;
  points.reserve(welded.positions.size());
  for (const Vec3d& q : welded.positions) points.push_back(to_point(q));

  std::vector<Face> faces;
  std::vector<Box> boxes;
  for (const Triangle& t : welded.triangles) {
    const CgalTriangle tri(points[t[0]], points[t[1]], points[t[2]]);
    if (tri.is_degenerate()) continue;
    boxes.emplace_back(tri.bbox(), faces.size());
    faces.push_back({t, tri});
  }
  std::int64_t count = 0;
  auto callback = [&](const Box& a, const Box& b) {
    if (faces_intersect(faces[a.info()], faces[b.info()], points)) ++count;
  };
  // Closed boxes so that faces touching at a single coordinate are still tested.
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), callback, std::ptrdiff_t(10),
                                CGAL::Box_intersection_d::CLOSED);
  return count;
}

}  // namespace mr::check
