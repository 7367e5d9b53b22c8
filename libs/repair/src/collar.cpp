#include "collar.h"

#include <mr/kernel/predicates.h>

#include <algorithm>
#include <unordered_map>

namespace mr::repair::detail {
namespace {

// Vertex stars that follow the splits, copied from the static stars the
// first time a vertex is asked for (only those near the defects are).
class DynamicStars {
 public:
  explicit DynamicStars(const TetMesh& mesh)
      : initial_(mesh.tets, mesh.positions.size()), initial_vertices_(mesh.positions.size()) {}
  const std::vector<Index>& of(Index v) { return star(v); }
  void add(Index v, Index t) { star(v).push_back(t); }
  void replace(Index v, Index old_tet, Index new_tet) {
    std::vector<Index>& s = star(v);
    std::replace(s.begin(), s.end(), old_tet, new_tet);
  }

 private:
  std::vector<Index>& star(Index v) {
    const auto [it, inserted] = stars_.try_emplace(v);
    if (inserted && v < initial_vertices_) it->second.assign(initial_.of(v).begin(), initial_.of(v).end());
    return it->second;
  }
  VertexStars initial_;
  std::size_t initial_vertices_;
  std::unordered_map<Index, std::vector<Index>> stars_;
};

Tet with_corner_replaced(Tet tet, Index from, Index to) {
  std::replace(tet.begin(), tet.end(), from, to);
  return tet;
}

// The tets around edge (v, x), when they close a ring around it (the
// other two corners of each tet, taken together, name every ring vertex
// twice); empty on the hull.
std::vector<Index> closed_ring(const TetMesh& mesh, DynamicStars& stars, Index v, Index x) {
  std::vector<Index> ring;
  std::vector<Index> others;
  for (Index t : stars.of(v)) {
    const Tet& tet = mesh.tets[t];
    if (!has_corner(tet, x)) continue;
    ring.push_back(t);
    for (Index c : tet)
      if (c != v && c != x) others.push_back(c);
  }
  std::sort(others.begin(), others.end());
  for (std::size_t i = 0; i < others.size(); i += 2) {
    const bool twice = i + 1 < others.size() && others[i] == others[i + 1] &&
                       (i + 2 == others.size() || others[i + 2] != others[i]);
    if (!twice) return {};
  }
  return ring;
}

bool positive(const std::vector<Vec3d>& p, const Tet& t) {
  return orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) > 0;
}

// Splits edge (v, x) at `point`: each tet around it becomes the part at x
// (in its slot) and the part at v (appended). False, changing nothing,
// when the edge is on the hull or a part would not be positive.
bool split_edge(TetMesh& mesh, std::vector<TetState>& states, DynamicStars& stars, Index v, Index x,
                const Vec3d& point) {
  const std::vector<Index> ring = closed_ring(mesh, stars, v, x);
  if (ring.empty()) return false;
  const auto w = static_cast<Index>(mesh.positions.size());
  mesh.positions.push_back(point);
  for (Index t : ring) {
    if (!positive(mesh.positions, with_corner_replaced(mesh.tets[t], v, w)) ||
        !positive(mesh.positions, with_corner_replaced(mesh.tets[t], x, w))) {
      mesh.positions.pop_back();
      return false;
    }
  }
  for (Index t : ring) {
    const Tet tet = mesh.tets[t];
    const auto at_v = static_cast<Index>(mesh.tets.size());
    mesh.tets[t] = with_corner_replaced(tet, v, w);
    mesh.tets.push_back(with_corner_replaced(tet, x, w));
    states.push_back(states[t]);
    stars.replace(v, t, at_v);
    stars.add(w, t);
    stars.add(w, at_v);
    for (Index c : tet)
      if (c != v && c != x) stars.add(c, at_v);
  }
  return true;
}

}  // namespace

std::size_t build_collars(TetMesh& mesh, std::vector<TetState>& states, std::span<const Index> centres,
                          double width) {
  DynamicStars stars(mesh);
  const auto is_centre = [&](Index v) { return std::binary_search(centres.begin(), centres.end(), v); };
  std::size_t splits = 0;
  for (Index v : centres) {
    std::vector<Index> neighbours;
    for (Index t : stars.of(v))
      for (Index c : mesh.tets[t])
        if (c != v) neighbours.push_back(c);
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    for (Index x : neighbours) {
      if (is_centre(x)) continue;
      const Vec3d& a = mesh.positions[v];
      const Vec3d& b = mesh.positions[x];
      const double length = (b - a).norm();
      if (!(length > width)) continue;
      const Vec3d point = a + (width / length) * (b - a);
      splits += split_edge(mesh, states, stars, v, x, point);
    }
  }
  return splits;
}

}  // namespace mr::repair::detail
