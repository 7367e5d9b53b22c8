#pragma once
// Option values shared by several functions of the module.

#include <mr/core/coordinate_grid.h>

#include <string>

namespace mr::python {

/// The grid output positions are rounded to: "float64" (none) or "float32"
/// (a mesh that stays watertight when written to STL or GLB).
CoordinateGrid grid_named(const std::string& name);

/// `threads` checked (0: all hardware threads); mr::UsageError when negative.
int checked_threads(int threads);

/// `value` checked >= 0; mr::UsageError naming `option` when negative.
int non_negative(const char* option, int value);

}  // namespace mr::python
