#pragma once
// Exact intersection tests for triangle insertion, built only from the exact
// predicates: every coplanar, collinear and touching case is classified, never
// decided by a tolerance. Each test has a double and a hybrid overload; the
// hybrid one accepts constructed (rational) points, and a double point
// converts to a hybrid one implicitly for mixed calls.
//
// Conventions: triangle (p, q, r); its vertex i is (p, q, r)[i] and its edge
// i joins vertex i and vertex (i + 1) % 3 (edge 0 = pq, 1 = qr, 2 = rp).
// Segment [a, b]: a is its source, b its target. All sets are closed.
// Preconditions: triangles are non-degenerate (their vertices are not
// collinear); a violated precondition that the test notices raises
// mr::UsageError. Segments may be degenerate (a == b).

#include <mr/kernel/hybrid_point.h>

namespace mr {

/// Where an endpoint or the whole edge [a, b] lies relative to the oriented
/// plane through p, q, r: each side is orient3d(p, q, r, endpoint).
struct PlaneEdgeSides {
  int source = 0;
  int target = 0;

  /// Endpoints strictly on opposite sides: the edge interior crosses the plane.
  bool crosses() const { return source * target < 0; }
  /// The edge meets the plane (crossing, touching it with an endpoint, or in it).
  bool meets() const { return source * target <= 0; }
  bool in_plane() const { return source == 0 && target == 0; }
};

PlaneEdgeSides plane_edge_sides(const Vec3d& p, const Vec3d& q, const Vec3d& r, const Vec3d& a,
                                const Vec3d& b);
PlaneEdgeSides plane_edge_sides(const HybridPoint& p, const HybridPoint& q, const HybridPoint& r,
                                const HybridPoint& a, const HybridPoint& b);

enum class SegmentTriangleKind {
  none,      ///< no common point (including parallel and coplanar-disjoint)
  point,     ///< one common point, segment not in the plane: see the locations
  coplanar,  ///< segment lies in the triangle's plane and meets the triangle
};

enum class SegmentPart { interior, source, target };
enum class TrianglePart { interior, edge, vertex };

struct SegmentTriangleHit {
  SegmentTriangleKind kind = SegmentTriangleKind::none;
  /// For kind == point: where the common point lies on each primitive.
  SegmentPart on_segment = SegmentPart::interior;
  TrianglePart on_triangle = TrianglePart::interior;
  /// For on_triangle == edge or vertex: which one (see the conventions).
  int index = -1;
  /// The segment lies in the plane of the triangle (hit or not).
  bool in_plane = false;

  bool hits() const { return kind != SegmentTriangleKind::none; }
  /// A single point interior to both: the segment properly pierces the face.
  bool proper() const {
    return kind == SegmentTriangleKind::point && on_segment == SegmentPart::interior &&
           on_triangle == TrianglePart::interior;
  }
};

SegmentTriangleHit intersect_segment_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& p, const Vec3d& q,
                                              const Vec3d& r);
SegmentTriangleHit intersect_segment_triangle(const HybridPoint& a, const HybridPoint& b,
                                              const HybridPoint& p, const HybridPoint& q,
                                              const HybridPoint& r);

enum class TriangleTriangleKind {
  disjoint,          ///< no common point
  shared_vertex,     ///< the intersection is exactly one vertex of both
  shared_edge,       ///< the intersection is exactly one edge of both
  touching,          ///< the intersection is one point, not a common vertex
  crossing,          ///< not coplanar; the intersection is a segment, not a common edge
  coplanar_overlap,  ///< coplanar; the intersection is a segment (not a common
                     ///< edge) or has area (identical triangles included)
};

struct TriangleTriangleHit {
  TriangleTriangleKind kind = TriangleTriangleKind::disjoint;
  /// Number of vertices the two triangles have in common (exact equality).
  int shared_vertices = 0;

  bool intersects() const { return kind != TriangleTriangleKind::disjoint; }
  /// Meeting in more than a common vertex or edge: what a valid surface
  /// mesh must never contain.
  bool improper() const {
    return kind == TriangleTriangleKind::touching || kind == TriangleTriangleKind::crossing ||
           kind == TriangleTriangleKind::coplanar_overlap;
  }
};

TriangleTriangleHit intersect_triangles(const Vec3d& p1, const Vec3d& q1, const Vec3d& r1, const Vec3d& p2,
                                        const Vec3d& q2, const Vec3d& r2);
TriangleTriangleHit intersect_triangles(const HybridPoint& p1, const HybridPoint& q1, const HybridPoint& r1,
                                        const HybridPoint& p2, const HybridPoint& q2, const HybridPoint& r2);

}  // namespace mr
