#pragma once
// Small keys and tests on faces shared by the hole-filling parts.

#include <mr/core/types.h>

#include <algorithm>
#include <cstdint>
#include <utility>

namespace mr::hole_fill::detail {

/// The edge a -> b as one integer.
inline std::uint64_t directed_edge_key(Index a, Index b) { return (std::uint64_t(a) << 32) | b; }

/// The edge {a, b}, either way round, as one integer.
inline std::uint64_t edge_key(Index a, Index b) {
  return a < b ? directed_edge_key(a, b) : directed_edge_key(b, a);
}

/// A face's corners in increasing order: the key of its vertex set.
inline Triangle sorted_corners(Triangle t) {
  std::sort(t.begin(), t.end());
  return t;
}

/// A face naming one vertex twice (no edge structure; skipped everywhere).
inline bool repeats_a_vertex(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

}  // namespace mr::hole_fill::detail
