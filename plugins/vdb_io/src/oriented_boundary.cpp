#include "vdb_level_set.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <unordered_map>

namespace mr::plugins::vdb {
namespace {

struct PositionHash {
  std::size_t operator()(const Vec3d& p) const {
    std::size_t h = 0;
    for (int i = 0; i < 3; ++i)
      h = h * 1000003u ^ std::hash<std::uint64_t>()(std::bit_cast<std::uint64_t>(p[i]));
    return h;
  }
};

// Maps each vertex to the first vertex with the same coordinates, so that
// soups with unmerged vertices (e.g. from STL) are judged by their geometry.
std::vector<Index> merge_equal_positions(const TriangleSoup& soup) {
  std::unordered_map<Vec3d, Index, PositionHash> first_at;
  std::vector<Index> canonical(soup.positions.size());
  for (std::size_t i = 0; i < soup.positions.size(); ++i)
    canonical[i] = first_at.try_emplace(soup.positions[i], static_cast<Index>(i)).first->second;
  return canonical;
}

}  // namespace

bool has_oriented_boundary(const TriangleSoup& soup) {
  const std::vector<Index> canonical = merge_equal_positions(soup);
  // Net count of each undirected edge: +1 for a -> b, -1 for b -> a (a < b).
  std::unordered_map<std::uint64_t, int> net;
  net.reserve(soup.triangles.size() * 2);
  for (const Triangle& t : soup.triangles) {
    const Index v[3] = {canonical[t[0]], canonical[t[1]], canonical[t[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int e = 0; e < 3; ++e) {
      const Index a = v[e], b = v[(e + 1) % 3];
      const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
      net[key] += a < b ? 1 : -1;
    }
  }
  for (const auto& [edge, count] : net)
    if (count != 0) return true;
  return false;
}

}  // namespace mr::plugins::vdb
