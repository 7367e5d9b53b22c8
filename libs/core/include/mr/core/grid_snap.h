#pragma once
// Snapping positions to a grid of power-of-two spacing. CAD exports and
// float files put coordinates that should be equal a rounding error apart;
// triangles through them cut each other in points closer together than a
// double can tell, which no mesh with double coordinates can hold. On a
// coarser grid the noise is gone: nearly coplanar faces become coplanar and
// nearly equal coordinates equal.

#include <mr/core/triangle_soup.h>

#include <cstddef>

namespace mr {

/// The largest power of two not above `bound` (> 0, finite, normal).
double power_of_two_at_most(double bound);

/// Rounds every coordinate of `soup` to the nearest multiple of `spacing`
/// (ties to even), exactly: `spacing` must be a power of two. Triangles are
/// kept as they are, even those that become degenerate, so their indices
/// still name the same input triangles. Returns how many positions moved;
/// each moves by at most spacing * sqrt(3) / 2.
std::size_t snap_to_grid(TriangleSoup& soup, double spacing);

}  // namespace mr
