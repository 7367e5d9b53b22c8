#pragma once
// Keys and small helpers shared by the parts of the triangle inserter
// (triangle_inserter*.cpp).

#include <mr/core/types.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace mr::tetmesh::detail {

/// A tet's six edges as pairs of corners.
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges{
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

/// `ids` (sorted) with `id` in its place.
inline std::vector<std::uint32_t> with_id(std::vector<std::uint32_t> ids, std::uint32_t id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
    ids.insert(std::upper_bound(ids.begin(), ids.end(), id), id);
  }
  return ids;
}

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
