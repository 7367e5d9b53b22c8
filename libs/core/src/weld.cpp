#include <mr/core/weld.h>

#include <array>
#include <bit>
#include <cstdint>
#include <unordered_map>

namespace mr {
namespace {

using Bits = std::array<std::uint64_t, 3>;

struct BitsHash {
  std::size_t operator()(const Bits& b) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (std::uint64_t x : b) h = (h ^ x) * 0xff51afd7ed558ccdull + (h >> 29);
    return static_cast<std::size_t>(h);
  }
};

// Adding +0 turns -0 into +0: the two are the same coordinate (a file
// that writes "-0" on one side of a seam and "0" on the other is closed).
Bits bits_of(const Vec3d& p) {
  return {std::bit_cast<std::uint64_t>(p.x() + 0.0), std::bit_cast<std::uint64_t>(p.y() + 0.0),
          std::bit_cast<std::uint64_t>(p.z() + 0.0)};
}

}  // namespace

TriangleSoup weld_identical_vertices(const TriangleSoup& soup) {
  std::vector<Index> welded_index;
  return weld_identical_vertices(soup, welded_index);
}

TriangleSoup weld_identical_vertices(const TriangleSoup& soup, std::vector<Index>& remap) {
  TriangleSoup welded;
  std::unordered_map<Bits, Index, BitsHash> first_index;
  first_index.reserve(soup.positions.size());
  remap.assign(soup.positions.size(), 0);
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    const auto [it, inserted] =
        first_index.try_emplace(bits_of(soup.positions[i]), static_cast<Index>(welded.positions.size()));
    if (inserted) welded.positions.push_back(soup.positions[i]);
    remap[i] = it->second;
  }
  welded.triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles)
    welded.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return welded;
}

}  // namespace mr
