#pragma once
// Private helpers for coplanar configurations: points in one plane are
// compared through the projection that drops one coordinate axis. Any axis
// for which a non-degenerate triangle of the plane projects to a
// non-degenerate triangle makes the projection a bijection of the plane, so
// exact 2D predicates on the projections decide the 3D coplanar question.

#include <mr/core/errors.h>
#include <mr/kernel/hybrid_point.h>

namespace mr::detail {

/// A projection axis for the plane of (p, q, r) and the sign of the projected
/// triangle on it (never 0). Throws UsageError for a degenerate triangle.
struct Projection {
  int axis = 2;
  int sign = 1;
};

/// Coordinate k, exactly: a double for a double point, a rational otherwise.
inline double coordinate(const Vec3d& p, int k) { return p[k]; }
inline mpq_class coordinate(const HybridPoint& p, int k) {
  return p.exact ? (*p.exact)[k] : mpq_class(p.approx[k]);
}

template <class P>
Projection projection_for(const P& p, const P& q, const P& r) {
  for (int axis = 2; axis >= 0; --axis) {
    const int sign = orient2d_projected(p, q, r, axis);
    if (sign != 0) return {axis, sign};
  }
  throw UsageError("exact intersection test: degenerate (collinear) triangle");
}

/// Orientation of (u, v, x) in the projection, made positive for the
/// counter-clockwise sense of the reference triangle.
template <class P>
int side(const Projection& proj, const P& u, const P& v, const P& x) {
  return proj.sign * orient2d_projected(u, v, x, proj.axis);
}

/// Whether coplanar point x lies in the closed triangle (t[0], t[1], t[2]).
template <class P>
bool in_triangle(const Projection& proj, const P* const t[3], const P& x) {
  for (int i = 0; i < 3; ++i) {
    if (side(proj, *t[i], *t[(i + 1) % 3], x) < 0) return false;
  }
  return true;
}

}  // namespace mr::detail
