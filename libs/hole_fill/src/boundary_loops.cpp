#include "boundary_loops.h"
#include "mesh_keys.h"

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

// One step of a walk: an edge and whether it was walked from `to` to `from`.
struct Step {
  std::size_t edge;
  bool reversed;
};

std::vector<BorderEdge> border_edges(const TriangleSoup& soup) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(soup.triangles.size() * 3);
  for (const Triangle& t : soup.triangles) {
    if (repeats_a_vertex(t)) continue;
    for (int i = 0; i < 3; ++i) ++uses[edge_key(t[i], t[(i + 1) % 3])];
  }
  std::vector<BorderEdge> border;
  for (const Triangle& t : soup.triangles) {
    if (repeats_a_vertex(t)) continue;
    for (int i = 0; i < 3; ++i) {
      const Index a = t[i], b = t[(i + 1) % 3];
      if (uses[edge_key(a, b)] == 1) border.push_back({b, a, t[(i + 2) % 3], false});
    }
  }
  return border;
}

Index start_of(const BorderEdge& e, bool reversed) { return reversed ? e.to : e.from; }
Index end_of(const BorderEdge& e, bool reversed) { return reversed ? e.from : e.to; }

// The loop of `steps`, turned the way most of its edges' faces ask (they
// all agree where the faces around the hole are oriented consistently).
BorderLoop make_loop(const std::vector<BorderEdge>& edges, std::vector<Step> steps) {
  const auto forward = std::count_if(steps.begin(), steps.end(), [](const Step& s) { return !s.reversed; });
  if (2 * std::size_t(forward) < steps.size()) {
    std::reverse(steps.begin(), steps.end());
    for (Step& s : steps) s.reversed = !s.reversed;
  }
  BorderLoop loop;
  for (const Step& s : steps) {
    loop.vertices.push_back(start_of(edges[s.edge], s.reversed));
    loop.opposite.push_back(edges[s.edge].opposite);
  }
  return loop;
}

// Walks from `start`, cutting off a loop each time the walk returns to a
// vertex on its path. Edges are followed either way round, so a border
// whose faces disagree on orientation still closes. Returns the number of
// edges left on a path that cannot close (a vertex with an odd number of
// border edges).
std::size_t walk_loops(std::vector<BorderEdge>& edges,
                       const std::unordered_multimap<Index, std::size_t>& incident, std::size_t start,
                       std::vector<BorderLoop>& loops) {
  std::vector<Step> path;
  std::unordered_map<Index, std::size_t> on_path;  // vertex -> position of the step leaving it
  Step step{start, false};
  while (true) {
    BorderEdge& e = edges[step.edge];
    e.used = true;
    on_path[start_of(e, step.reversed)] = path.size();
    path.push_back(step);
    const Index head = end_of(e, step.reversed);
    auto back = on_path.find(head);
    if (back != on_path.end()) {
      const std::size_t first = back->second;
      for (std::size_t k = first; k < path.size(); ++k)
        on_path.erase(start_of(edges[path[k].edge], path[k].reversed));
      loops.push_back(make_loop(edges, std::vector<Step>(path.begin() + std::ptrdiff_t(first), path.end())));
      path.resize(first);
      if (path.empty()) return 0;
    }
    // Go on from the head with the lowest unused edge at it, either way round.
    std::size_t next = edges.size();
    auto [lo, hi] = incident.equal_range(head);
    for (auto it = lo; it != hi; ++it)
      if (!edges[it->second].used) next = std::min(next, it->second);
    if (next == edges.size()) return path.size();
    step = {next, edges[next].from != head};
  }
}

}  // namespace

BorderLoops find_border_loops(const TriangleSoup& welded) {
  std::vector<BorderEdge> edges = border_edges(welded);
  std::unordered_multimap<Index, std::size_t> incident;
  incident.reserve(2 * edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    incident.emplace(edges[i].from, i);
    incident.emplace(edges[i].to, i);
  }
  BorderLoops result;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (!edges[i].used) result.open_edges += walk_loops(edges, incident, i, result.loops);
  return result;
}

}  // namespace mr::hole_fill::detail
