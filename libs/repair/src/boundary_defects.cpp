#include "boundary_defects.h"

#include <mr/core/union_find.h>

#include <algorithm>
#include <tuple>

namespace mr::repair::detail {
namespace {

struct EdgeUse {
  Index a, b;  // a < b
  std::size_t face;
  int corner_a, corner_b;  // corners of the face holding a and b
};

std::vector<EdgeUse> edge_uses(std::span<const Triangle> triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      int ca = i, cb = (i + 1) % 3;
      if (triangles[f][ca] > triangles[f][cb]) std::swap(ca, cb);
      uses.push_back({triangles[f][ca], triangles[f][cb], f, ca, cb});
    }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.a, x.b, x.face) < std::tie(y.a, y.b, y.face);
  });
  return uses;
}

}  // namespace

BoundaryDefects find_boundary_defects(std::span<const Triangle> triangles) {
  BoundaryDefects defects;
  const std::vector<EdgeUse> uses = edge_uses(triangles);
  UnionFind corners(3 * triangles.size());  // over face corners, 3 per face
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    if (j - i == 1) ++defects.boundary_edges;
    if (j - i > 2) defects.nonmanifold_edges.push_back({uses[i].a, uses[i].b});
    for (std::size_t k = i + 1; k < j; ++k) {
      corners.unite(3 * uses[i].face + uses[i].corner_a, 3 * uses[k].face + uses[k].corner_a);
      corners.unite(3 * uses[i].face + uses[i].corner_b, 3 * uses[k].face + uses[k].corner_b);
    }
    i = j;
  }
  std::vector<std::pair<Index, std::size_t>> fans;  // (vertex, root of one of its corners)
  fans.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) fans.emplace_back(triangles[f][c], corners.find(3 * f + c));
  std::sort(fans.begin(), fans.end());
  fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
  for (std::size_t i = 1; i < fans.size(); ++i)
    if (fans[i].first == fans[i - 1].first &&
        (defects.nonmanifold_vertices.empty() || defects.nonmanifold_vertices.back() != fans[i].first))
      defects.nonmanifold_vertices.push_back(fans[i].first);
  return defects;
}

}  // namespace mr::repair::detail
