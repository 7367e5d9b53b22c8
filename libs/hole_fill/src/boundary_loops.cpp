#include "boundary_loops.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace mr::hole_fill::detail {
namespace {

struct BorderEdge {
  Index from = 0;  ///< the hole's direction: the reverse of the face's edge
  Index to = 0;
  Index opposite = 0;
  bool used = false;
};

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(a) << 32) | b;
}

bool degenerate(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

std::vector<BorderEdge> border_edges(const TriangleSoup& soup) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(soup.triangles.size() * 3);
  for (const Triangle& t : soup.triangles) {
    if (degenerate(t)) continue;
    for (int i = 0; i < 3; ++i) ++uses[edge_key(t[i], t[(i + 1) % 3])];
  }
  std::vector<BorderEdge> border;
  for (const Triangle& t : soup.triangles) {
    if (degenerate(t)) continue;
    for (int i = 0; i < 3; ++i) {
      const Index a = t[i], b = t[(i + 1) % 3];
      if (uses[edge_key(a, b)] == 1) border.push_back({b, a, t[(i + 2) % 3], false});
    }
  }
  return border;
}

// Walks from `start`, cutting off a loop each time the walk returns to a
// vertex on its path, until the path is empty (it always ends where it
// began: every vertex has as many border edges in as out).
void walk_loops(std::vector<BorderEdge>& edges, const std::unordered_multimap<Index, std::size_t>& outgoing,
                std::size_t start, std::vector<BorderLoop>& loops) {
  std::vector<std::size_t> path;                  // edge ids
  std::unordered_map<Index, std::size_t> on_path; // vertex -> position in path of the edge leaving it
  std::size_t current = start;
  while (true) {
    BorderEdge& e = edges[current];
    e.used = true;
    on_path[e.from] = path.size();
    path.push_back(current);
    auto back = on_path.find(e.to);
    if (back != on_path.end()) {
      BorderLoop loop;
      for (std::size_t k = back->second; k < path.size(); ++k) {
        loop.vertices.push_back(edges[path[k]].from);
        loop.opposite.push_back(edges[path[k]].opposite);
        on_path.erase(edges[path[k]].from);
      }
      path.resize(back->second);
      loops.push_back(std::move(loop));
      if (path.empty()) return;
    }
    // Continue from the head of the path with the lowest unused edge leaving it.
    const Index head = edges[current].to;
    std::size_t next = edges.size();
    auto [first, last] = outgoing.equal_range(head);
    for (auto it = first; it != last; ++it)
      if (!edges[it->second].used) next = std::min(next, it->second);
    if (next == edges.size()) return;  // only on an inconsistent input; the loop stays open
    current = next;
  }
}

}  // namespace

std::vector<BorderLoop> find_border_loops(const TriangleSoup& welded) {
  std::vector<BorderEdge> edges = border_edges(welded);
  std::unordered_multimap<Index, std::size_t> outgoing;
  outgoing.reserve(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) outgoing.emplace(edges[i].from, i);
  std::vector<BorderLoop> loops;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (!edges[i].used) walk_loops(edges, outgoing, i, loops);
  return loops;
}

}  // namespace mr::hole_fill::detail
