#include <mr/kernel/constructions.h>

#include "homogeneous.h"

#include <mr/core/errors.h>

namespace mr {
namespace {

using Normal = std::array<mpz_class, 3>;

// The normal of the plane through p, q, r, times a positive factor k.
Normal scaled_normal(const detail::Homogeneous& hp, const HybridPoint& q, const HybridPoint& r) {
  const auto u = detail::scaled_difference(detail::homogeneous(q.to_exact()), hp);
  const auto v = detail::scaled_difference(detail::homogeneous(r.to_exact()), hp);
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// normal . (x - p), times x.w * p.w.
mpz_class scaled_side(const Normal& normal, const detail::Homogeneous& x, const detail::Homogeneous& hp) {
  const auto d = detail::scaled_difference(x, hp);
  return normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2];
}

}  // namespace

ExactPoint3 intersect_segment_plane(const HybridPoint& a, const HybridPoint& b, const HybridPoint& p,
                                    const HybridPoint& q, const HybridPoint& r) {
  // On integers over common denominators (detail::Homogeneous): a chain of
  // mpq operations reduces every intermediate by a gcd; this reduces the
  // three coordinates once, at the end.
  const detail::Homogeneous ha = detail::homogeneous(a.to_exact()), hb = detail::homogeneous(b.to_exact());
  const detail::Homogeneous hp = detail::homogeneous(p.to_exact());
  const Normal normal = scaled_normal(hp, q, r);
  // The sides of a and b, each times a positive factor k * a.w (b.w).
  const mpz_class sa = scaled_side(normal, ha, hp), sb = scaled_side(normal, hb, hp);
  if (sgn(sa) * sgn(sb) > 0 || (sgn(sa) == 0 && sgn(sb) == 0)) {
    throw UsageError("intersect_segment_plane: the segment does not cross the plane at one point");
  }
  // The side is affine along the segment; it vanishes at
  // (sa b - sb a) / (sa b.w - sb a.w) once the factors a.w, b.w are divided out.
  const mpz_class denominator = sa * hb.w - sb * ha.w;
  const auto coordinate = [&](const mpz_class& xa, const mpz_class& xb) {
    mpq_class c(sa * xb - sb * xa, denominator);
    c.canonicalize();
    return c;
  };
  return {coordinate(ha.x, hb.x), coordinate(ha.y, hb.y), coordinate(ha.z, hb.z)};
}

ExactPoint3 move_onto_plane_along_axis(const HybridPoint& a, int axis, const HybridPoint& p,
                                       const HybridPoint& q, const HybridPoint& r) {
  const detail::Homogeneous ha = detail::homogeneous(a.to_exact()), hp = detail::homogeneous(p.to_exact());
  const Normal normal = scaled_normal(hp, q, r);
  if (axis < 0 || axis > 2 || sgn(normal[axis]) == 0) {
    throw UsageError("move_onto_plane_along_axis: the plane is parallel to the axis");
  }
  // side = normal . (a - p) * a.w * p.w, normal the true one times a positive
  // factor k; a moves by -side / (a.w * p.w * normal[axis]) along the axis.
  const mpz_class side = scaled_side(normal, ha, hp);
  const mpz_class& along = axis == 0 ? ha.x : axis == 1 ? ha.y : ha.z;
  mpq_class moved(along * hp.w * normal[axis] - side, ha.w * hp.w * normal[axis]);
  moved.canonicalize();
  ExactPoint3 out = a.to_exact();
  (axis == 0 ? out.x : axis == 1 ? out.y : out.z) = std::move(moved);
  return out;
}

std::optional<ExactPoint3> intersect_segment_triangle_point(const HybridPoint& a, const HybridPoint& b,
                                                            const HybridPoint& p, const HybridPoint& q,
                                                            const HybridPoint& r) {
  const SegmentTriangleHit hit = intersect_segment_triangle(a, b, p, q, r);
  if (hit.kind != SegmentTriangleKind::point) return std::nullopt;
  return intersect_segment_plane(a, b, p, q, r);
}

}  // namespace mr
