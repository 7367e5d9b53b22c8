#include <mr/hole_fill/holes_only.h>

#include "filled_surface.h"
#include "mesh_keys.h"

#include <mr/core/weld.h>
#include <mr/kernel/predicates.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mr::hole_fill {
namespace {

std::string face_refusal(const TriangleSoup& soup) {
  std::vector<std::array<Index, 3>> corner_sets;
  corner_sets.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) {
    if (detail::repeats_a_vertex(t) ||
        collinear(soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]))
      return "a face is degenerate";
    std::array<Index, 3>& sorted = corner_sets.emplace_back(t);
    std::sort(sorted.begin(), sorted.end());
  }
  std::sort(corner_sets.begin(), corner_sets.end());
  if (std::adjacent_find(corner_sets.begin(), corner_sets.end()) != corner_sets.end())
    return "a face is repeated";
  return {};
}

// Every directed edge once (else an edge has more than two faces or two
// faces disagree on orientation); some edge without its reverse (a hole),
// unless a closed surface is accepted.
std::string edge_refusal(const TriangleSoup& soup, bool accept_closed) {
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(soup.triangles.size() * 3);
  for (const Triangle& t : soup.triangles)
    for (int i = 0; i < 3; ++i)
      if (++directed[detail::directed_edge_key(t[i], t[(i + 1) % 3])] > 1)
        return "an edge has more than two faces or its faces disagree on orientation";
  if (accept_closed) return {};
  for (const auto& [key, count] : directed)
    if (!directed.count(detail::directed_edge_key(Index(key & 0xffffffffu), Index(key >> 32)))) return {};
  return "no hole";
}

}  // namespace

std::string defects_other_than_holes(const TriangleSoup& input, bool accept_closed) {
  TriangleSoup welded = weld_identical_vertices(input);
  if (std::string why = face_refusal(welded); !why.empty()) return why;
  if (std::string why = edge_refusal(welded, accept_closed); !why.empty()) return why;
  if (detail::FilledSurface(std::move(welded)).meets_itself())
    return "faces meet away from their shared vertices and edges";
  return {};
}

}  // namespace mr::hole_fill
