#pragma once
// Exact predicates used by the checks (CGAL's filtered Epick predicates,
// kept in one translation unit).

#include <mr/core/types.h>

#include <vector>

namespace mr::check::detail {

/// True if a, b, c lie exactly on one line (or coincide).
bool exactly_collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c);

/// Sign of ((b-a)x(c-a)).(d-a), exactly: -1, 0 or +1.
int orient3d_sign(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

/// det[b-a, c-a, d-a] (six times the signed volume), computed exactly and
/// rounded to a double of the same sign.
double exact_orient3d_value(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

/// Six times the volume the triangles enclose (each a cone from the origin),
/// summed exactly, rounded to a double of the same sign.
double exact_six_volume(const std::vector<Vec3d>& positions, const std::vector<Triangle>& triangles);

}  // namespace mr::check::detail
