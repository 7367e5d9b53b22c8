#pragma once
// Exact predicates used by the checks (CGAL's filtered Epick predicates,
// kept in one translation unit).

#include <mr/core/types.h>

namespace mr::check::detail {

/// True if a, b, c lie exactly on one line (or coincide).
bool exactly_collinear(const Vec3d& a, const Vec3d& b, const Vec3d& c);

/// Sign of ((b-a)x(c-a)).(d-a), exactly: -1, 0 or +1.
int orient3d_sign(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

}  // namespace mr::check::detail
