#include "welded.h"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace mr::check::detail {

Welded weld_identical(const TriangleSoup& soup) {
  const std::size_t n = soup.positions.size();
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index(0));
  auto key = [&](Index i) {
    const Vec3d& p = soup.positions[i];
    return std::make_tuple(p.x(), p.y(), p.z());
  };
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    const auto ka = key(a), kb = key(b);
    return ka < kb || (ka == kb && a < b);
  });
  Welded welded;
  std::vector<Index> remap(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (k == 0 || key(order[k]) != key(order[k - 1])) welded.positions.push_back(soup.positions[order[k]]);
    remap[order[k]] = static_cast<Index>(welded.positions.size() - 1);
  }
  welded.triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles)
    welded.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
  return welded;
}

}  // namespace mr::check::detail
