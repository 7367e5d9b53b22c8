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

#include <array>

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

/// The plane of a triangle (a, b, c), prepared for many questions about
/// which side of it a point lies on: the sign of orient3d(a, b, c, p) where
/// a floating-point evaluation certifies it, with the error bound of CGAL's
/// static filter for this determinant (evaluated in the same order), and 0
/// where it cannot (then ask orient3d). Half the arithmetic depends on the
/// plane only and is done once.
class PlaneSideFilter {
 public:
  PlaneSideFilter(const Vec3d& a, const Vec3d& b, const Vec3d& c);
  /// +1 or -1 when certain, else 0 (p may be on the plane or near it).
  int certain_sign(const Vec3d& p) const;
  /// True when p, q and r are certainly all strictly on one side: a
  /// triangle with these corners cannot meet triangle (a, b, c).
  bool certainly_one_side(const Vec3d& p, const Vec3d& q, const Vec3d& r) const {
    const int s = certain_sign(p);
    return s != 0 && certain_sign(q) == s && certain_sign(r) == s;
  }

 private:
  Vec3d a_, ab_, ac_;
  Vec3d largest_;  ///< per axis, the largest |coordinate| of b - a and c - a
  double minor_ = 0.0;
};

/// True when the corners of triangle q that are not corners of triangle p
/// (equal positions) are certainly all strictly on one side of p's plane
/// (`plane`, made from p). Then q meets that plane only in the corners it
/// shares with p, so the two meet, if at all, only in what they share:
/// never improperly. Faces around a vertex or an edge pass without the
/// exact test, which their shared corners (orientation exactly 0) would
/// send to exact arithmetic. False says nothing.
bool certainly_apart_but_shared(const PlaneSideFilter& plane, const std::array<Vec3d, 3>& p,
                                const std::array<Vec3d, 3>& q);

/// True if a, b and c lie on one line (or coincide), exactly.
inline bool collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return orient2d_projected(a, b, c, 0) == 0 && orient2d_projected(a, b, c, 1) == 0 &&
         orient2d_projected(a, b, c, 2) == 0;
}

}  // namespace mr
