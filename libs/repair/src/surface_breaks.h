// The whole-surface check of the rounding onto the output grid
// (round_to_grid.cpp): which moved vertices break the surface.

#pragma once

#include <mr/core/triangle_soup.h>

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace mr::repair {

/// Positions equal as doubles (0.0 and -0.0 alike) get one key: a reader welds them.
struct PositionHash {
  std::size_t operator()(const Vec3d& p) const {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) h = h * 0x9E3779B97F4A7C15ull + std::bit_cast<std::uint64_t>(p[k] + 0.0);
    return h;
  }
};
struct PositionEqual {
  bool operator()(const Vec3d& a, const Vec3d& b) const { return a == b; }
};

/// One flag per vertex of `surface`: flagged in `moved` and a corner of a
/// face that meets another improperly or has collinear corners, or on the
/// position of another vertex. Exact; the faces with a moved corner are
/// tested in parallel against the whole surface.
std::vector<std::uint8_t> vertices_breaking_surface(const TriangleSoup& surface,
                                                    std::span<const std::uint8_t> moved);

}  // namespace mr::repair
