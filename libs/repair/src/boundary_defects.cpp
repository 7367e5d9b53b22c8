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

// Rearranges `items` by key(item) in 0..keys-1, keeping their order within
// a key (counting sort), and returns where each key's run begins (keys + 1
// offsets). Run once per round of the manifold fix over every boundary
// corner: a comparison sort of them was most of its time on soups.
template <class T, class Key>
std::vector<std::size_t> group_by_key(std::vector<T>& items, std::size_t keys, Key&& key) {
  std::vector<std::size_t> begin(keys + 1, 0);
  for (const T& item : items) ++begin[key(item) + 1];
  for (std::size_t k = 0; k < keys; ++k) begin[k + 1] += begin[k];
  std::vector<T> grouped(items.size());
  std::vector<std::size_t> next(begin.begin(), begin.end() - 1);
  for (const T& item : items) grouped[next[key(item)]++] = item;
  items = std::move(grouped);
  return begin;
}

Index vertex_count(std::span<const Triangle> triangles) {
  Index largest = 0;
  for (const Triangle& t : triangles) largest = std::max({largest, t[0], t[1], t[2]});
  return triangles.empty() ? 0 : largest + 1;
}

// Every edge of every face once per face, sorted by (a, b, face): grouped
// by a in face order, then each vertex's few edges sorted by b.
std::vector<EdgeUse> edge_uses(std::span<const Triangle> triangles, Index vertices) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      int ca = i, cb = (i + 1) % 3;
      if (triangles[f][ca] > triangles[f][cb]) std::swap(ca, cb);
      uses.push_back({triangles[f][ca], triangles[f][cb], f, ca, cb});
    }
  const std::vector<std::size_t> begin = group_by_key(uses, vertices, [](const EdgeUse& u) { return u.a; });
  for (Index v = 0; v < vertices; ++v)
    std::sort(
        uses.begin() + static_cast<std::ptrdiff_t>(begin[v]),
        uses.begin() + static_cast<std::ptrdiff_t>(begin[v + 1]),
        [](const EdgeUse& x, const EdgeUse& y) { return std::tie(x.b, x.face) < std::tie(y.b, y.face); });
  return uses;
}

}  // namespace

BoundaryDefects find_boundary_defects(std::span<const Triangle> triangles) {
  BoundaryDefects defects;
  const Index vertices = vertex_count(triangles);
  const std::vector<EdgeUse> uses = edge_uses(triangles, vertices);
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
  // A vertex is non-manifold when its corners fall into more than one fan.
  std::vector<std::pair<Index, std::size_t>> fans;  // (vertex, root of one of its corners)
  fans.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) fans.emplace_back(triangles[f][c], corners.find(3 * f + c));
  const std::vector<std::size_t> begin =
      group_by_key(fans, vertices, [](const auto& fan) { return fan.first; });
  for (Index v = 0; v < vertices; ++v) {
    const auto first = fans.begin() + static_cast<std::ptrdiff_t>(begin[v]);
    const auto last = fans.begin() + static_cast<std::ptrdiff_t>(begin[v + 1]);
    if (std::any_of(first, last, [&](const auto& fan) { return fan.second != first->second; }))
      defects.nonmanifold_vertices.push_back(v);
  }
  return defects;
}

}  // namespace mr::repair::detail
