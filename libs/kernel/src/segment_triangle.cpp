// Plane/edge and segment/triangle classification from orient3d and
// projected orient2d only.

#include "coplanar.h"

#include <mr/kernel/intersections.h>

namespace mr {
namespace {

template <class P>
PlaneEdgeSides plane_edge_sides_impl(const P& p, const P& q, const P& r, const P& a, const P& b) {
  return {orient3d(p, q, r, a), orient3d(p, q, r, b)};
}

/// Segment and triangle in one plane: they meet unless a line through a
/// triangle edge or through the segment separates them strictly (separating
/// axis theorem for convex sets in the plane).
template <class P>
bool coplanar_segment_meets_triangle(const P& a, const P& b, const P* const t[3]) {
  const detail::Projection proj = detail::projection_for(*t[0], *t[1], *t[2]);
  for (int i = 0; i < 3; ++i) {
    const P& u = *t[i];
    const P& v = *t[(i + 1) % 3];
    if (detail::side(proj, u, v, a) < 0 && detail::side(proj, u, v, b) < 0) return false;
  }
  int positive = 0, negative = 0;
  for (int i = 0; i < 3; ++i) {
    const int s = orient2d_projected(a, b, *t[i], proj.axis);
    positive += s > 0;
    negative += s < 0;
  }
  return positive < 3 && negative < 3;
}

/// The line through a and b is known to cross the plane of the triangle at
/// one point X; locate X on the triangle from the orientation of the line
/// against each edge.
void locate_on_triangle(SegmentTriangleHit& hit, const std::array<int, 3>& edge_sides) {
  int zeros = 0, positive = 0, negative = 0;
  for (int s : edge_sides) {
    zeros += s == 0;
    positive += s > 0;
    negative += s < 0;
  }
  if (positive > 0 && negative > 0) {
    hit.kind = SegmentTriangleKind::none;
    return;
  }
  hit.kind = SegmentTriangleKind::point;
  if (zeros == 0) {
    hit.on_triangle = TrianglePart::interior;
  } else if (zeros == 1) {
    hit.on_triangle = TrianglePart::edge;
    hit.index = edge_sides[0] == 0 ? 0 : edge_sides[1] == 0 ? 1 : 2;
  } else {
    // Two edges through X: their common vertex. Edge i and edge i+1 share vertex i+1.
    hit.on_triangle = TrianglePart::vertex;
    hit.index = edge_sides[0] != 0 ? 2 : edge_sides[1] != 0 ? 0 : 1;
  }
}

template <class P>
SegmentTriangleHit segment_triangle_impl(const P& a, const P& b, const P& p, const P& q, const P& r) {
  SegmentTriangleHit hit;
  const PlaneEdgeSides sides = plane_edge_sides_impl(p, q, r, a, b);
  if (!sides.meets()) return hit;
  if (sides.in_plane()) {
    hit.in_plane = true;
    const P* const t[3] = {&p, &q, &r};
    if (coplanar_segment_meets_triangle(a, b, t)) hit.kind = SegmentTriangleKind::coplanar;
    return hit;
  }
  hit.on_segment = sides.source == 0   ? SegmentPart::source
                   : sides.target == 0 ? SegmentPart::target
                                       : SegmentPart::interior;
  locate_on_triangle(hit, {orient3d(a, b, p, q), orient3d(a, b, q, r), orient3d(a, b, r, p)});
  if (hit.kind == SegmentTriangleKind::none) hit = SegmentTriangleHit{};
  return hit;
}

}  // namespace

PlaneEdgeSides plane_edge_sides(const Vec3d& p, const Vec3d& q, const Vec3d& r, const Vec3d& a,
                                const Vec3d& b) {
  return plane_edge_sides_impl(p, q, r, a, b);
}

PlaneEdgeSides plane_edge_sides(const HybridPoint& p, const HybridPoint& q, const HybridPoint& r,
                                const HybridPoint& a, const HybridPoint& b) {
  return plane_edge_sides_impl(p, q, r, a, b);
}

SegmentTriangleHit intersect_segment_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& p, const Vec3d& q,
                                              const Vec3d& r) {
  return segment_triangle_impl(a, b, p, q, r);
}

SegmentTriangleHit intersect_segment_triangle(const HybridPoint& a, const HybridPoint& b,
                                              const HybridPoint& p, const HybridPoint& q,
                                              const HybridPoint& r) {
  return segment_triangle_impl(a, b, p, q, r);
}

}  // namespace mr
