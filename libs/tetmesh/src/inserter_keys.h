#pragma once
// Keys and small comparisons shared by the two halves of the triangle
// inserter (triangle_inserter.cpp, triangle_inserter_cavity.cpp).

#include <mr/core/types.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

namespace mr::tetmesh::detail {

/// A segment (unordered vertex pair) as one integer.
inline std::uint64_t segment_key(Index u, Index v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(u) << 32) | v;
}

/// A face's corners in increasing order: its key.
inline std::array<Index, 3> sorted_corners(std::array<Index, 3> c) {
  std::sort(c.begin(), c.end());
  return c;
}

/// Whether b is the cycle a with the same orientation.
inline bool same_orientation(const std::array<Index, 3>& a, const std::array<Index, 3>& b) {
  for (int i = 0; i < 3; ++i) {
    if (a[i] == b[0]) return a[(i + 1) % 3] == b[1];
  }
  return false;
}

}  // namespace mr::tetmesh::detail
