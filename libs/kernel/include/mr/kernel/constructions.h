#pragma once
// Exact constructions of the points a cut creates. Results are exact
// rationals: they lie exactly on the plane and on the segment (orient3d of
// the result against the plane is 0 in exact arithmetic). Wrap a result in
// HybridPoint::from_exact to get a mesh vertex, then try_round it once its
// incident tets exist.

#include <mr/kernel/intersections.h>

#include <optional>

namespace mr {

/// The point where segment [a, b] meets the plane through p, q, r.
/// Precondition (mr::UsageError otherwise): the segment meets the plane in
/// exactly one point, i.e. plane_edge_sides(p, q, r, a, b) meets() and is
/// not in_plane().
ExactPoint3 intersect_segment_plane(const HybridPoint& a, const HybridPoint& b, const HybridPoint& p,
                                    const HybridPoint& q, const HybridPoint& r);

/// Point a moved along coordinate axis `axis` (0, 1, 2) onto the plane
/// through p, q, r: only that coordinate changes. Precondition
/// (mr::UsageError otherwise): the plane is not parallel to the axis.
ExactPoint3 move_onto_plane_along_axis(const HybridPoint& a, int axis, const HybridPoint& p,
                                       const HybridPoint& q, const HybridPoint& r);

/// The common point of segment [a, b] and triangle (p, q, r) when they meet in
/// exactly one point with the segment outside the plane (SegmentTriangleKind::point);
/// std::nullopt when they are disjoint or the segment lies in the plane.
std::optional<ExactPoint3> intersect_segment_triangle_point(const HybridPoint& a, const HybridPoint& b,
                                                            const HybridPoint& p, const HybridPoint& q,
                                                            const HybridPoint& r);

}  // namespace mr
