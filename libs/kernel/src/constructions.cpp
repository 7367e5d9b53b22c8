#include <mr/kernel/constructions.h>

#include <mr/core/errors.h>

namespace mr {
namespace {

/// Six times the signed volume of (p, q, r, x), exactly.
mpq_class signed_volume(const ExactPoint3& p, const ExactPoint3& q, const ExactPoint3& r,
                        const ExactPoint3& x) {
  const mpq_class ux = q.x - p.x, uy = q.y - p.y, uz = q.z - p.z;
  const mpq_class vx = r.x - p.x, vy = r.y - p.y, vz = r.z - p.z;
  const mpq_class wx = x.x - p.x, wy = x.y - p.y, wz = x.z - p.z;
  return ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
}

}  // namespace

ExactPoint3 intersect_segment_plane(const HybridPoint& a, const HybridPoint& b,
                                    const HybridPoint& p, const HybridPoint& q,
                                    const HybridPoint& r) {
  const ExactPoint3 ea = a.to_exact(), eb = b.to_exact();
  const ExactPoint3 ep = p.to_exact(), eq = q.to_exact(), er = r.to_exact();
  const mpq_class va = signed_volume(ep, eq, er, ea);
  const mpq_class vb = signed_volume(ep, eq, er, eb);
  if (sgn(va) * sgn(vb) > 0 || (sgn(va) == 0 && sgn(vb) == 0)) {
    throw UsageError("intersect_segment_plane: the segment does not cross the plane at one point");
  }
  // The volume is affine along the segment: it vanishes at t = va / (va - vb).
  const mpq_class t = va / (va - vb);
  return {ea.x + t * (eb.x - ea.x), ea.y + t * (eb.y - ea.y), ea.z + t * (eb.z - ea.z)};
}

std::optional<ExactPoint3> intersect_segment_triangle_point(const HybridPoint& a,
                                                            const HybridPoint& b,
                                                            const HybridPoint& p,
                                                            const HybridPoint& q,
                                                            const HybridPoint& r) {
  const SegmentTriangleHit hit = intersect_segment_triangle(a, b, p, q, r);
  if (hit.kind != SegmentTriangleKind::point) return std::nullopt;
  return intersect_segment_plane(a, b, p, q, r);
}

}  // namespace mr
