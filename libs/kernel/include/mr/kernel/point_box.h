#pragma once
// Certified boxes around points: a filter for decisions on points that are
// costly to construct exactly. A cut point is a GMP rational; most tests on
// it (which side of a line it lies) are decided by interval arithmetic on a
// box that surely contains it, and only the undecided ones need the exact
// point. Boxes come from directed rounding (CGAL's Interval_nt), so a sign
// reported certain is the sign for every point of the box.

#include <mr/kernel/hybrid_point.h>

#include <optional>

namespace mr {

/// A closed axis-aligned box that contains a point.
struct PointBox {
  Vec3d lo, hi;
};

/// Returned by the box predicates when the sign differs within the boxes or
/// the filter cannot tell.
inline constexpr int kUncertainSign = 2;

/// The box of a hybrid point: a double itself, or the neighbours of the
/// rational's nearest double.
PointBox box_of(const HybridPoint& p);

/// A box containing the point where segment (a, b) crosses the plane
/// through p, q, r, for a segment with a and b strictly on opposite sides
/// (as intersect_segment_plane requires). nullopt when interval arithmetic
/// cannot bound it.
std::optional<PointBox> box_of_segment_plane(const HybridPoint& a, const HybridPoint& b, const HybridPoint& p,
                                             const HybridPoint& q, const HybridPoint& r);

/// orient2d_projected (hybrid_point.h) for points known only by boxes: the
/// sign if it is the same for every choice of points in the boxes and the
/// filter proves it, kUncertainSign otherwise.
int orient2d_projected(const PointBox& a, const PointBox& b, const PointBox& c, int axis);

}  // namespace mr
