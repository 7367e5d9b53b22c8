#pragma once
// Exact geometric predicates on double coordinates.
//
// Every function returns the exact sign (-1, 0 or +1) of a polynomial in the
// input coordinates, as if it were evaluated with infinite precision: a fast
// floating-point evaluation with a proven error bound answers almost every
// call; only when the bound cannot certify the sign is the predicate
// re-evaluated exactly. The answers are therefore consistent with each other
// and never flip under rounding, which is what the topological decisions of
// triangle insertion and mesh improvement rely on.
//
// Sign conventions (shared by the exact and hybrid versions in exact_point.h
// and hybrid_point.h, and by mr::TetMesh, whose tets all have orient3d > 0):
//   orient2d(a, b, c)       > 0 iff (b - a) x (c - a) > 0: a, b, c turn counter-clockwise.
//   orient3d(a, b, c, d)    > 0 iff ((b - a) x (c - a)) . (d - a) > 0: positive tet volume,
//                               i.e. d lies on the side the normal of the
//                               counter-clockwise triangle a, b, c points to.
//   incircle(a, b, c, d)    > 0 iff d is strictly inside the circle through a, b, c
//                               when orient2d(a, b, c) > 0 (the sign flips otherwise).
//   insphere(a, b, c, d, e) > 0 iff e is strictly inside the sphere through a, b, c, d
//                               when orient3d(a, b, c, d) > 0 (the sign flips otherwise).
//
// Precondition: finite coordinates (no NaN or infinity). Any finite magnitude
// works; subnormal and huge values simply take the exact path.

#include <mr/core/types.h>

namespace mr {

using Vec2d = Eigen::Vector2d;

int orient2d(const Vec2d& a, const Vec2d& b, const Vec2d& c);
int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
int incircle(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d);
int insphere(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d, const Vec3d& e);

/// orient2d of the projections of a, b, c onto the coordinate plane that
/// drops coordinate `axis` (0, 1 or 2); the two kept coordinates stay in
/// increasing order, e.g. axis 0 keeps (y, z).
int orient2d_projected(const Vec3d& a, const Vec3d& b, const Vec3d& c, int axis);

/// The axis along which a plane with this normal projects best (its largest
/// normal component; the first of equal ones): where orient2d_projected is
/// best conditioned. A choice, not a predicate.
inline int dominant_axis(const Vec3d& normal) {
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  return axis;
}

/// True if a, b and c lie on one line (or coincide), exactly.
inline bool collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return orient2d_projected(a, b, c, 0) == 0 && orient2d_projected(a, b, c, 1) == 0 &&
         orient2d_projected(a, b, c, 2) == 0;
}

}  // namespace mr
