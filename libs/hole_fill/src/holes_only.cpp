#include <mr/hole_fill/holes_only.h>

#include "filled_surface.h"
#include "mesh_keys.h"

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
    corner_sets.push_back(detail::sorted_corners(t));
  }
  std::sort(corner_sets.begin(), corner_sets.end());
  if (std::adjacent_find(corner_sets.begin(), corner_sets.end()) != corner_sets.end())
    return "a face is repeated";
  return {};
}

// Every directed edge once (else an edge has more than two faces or two
// faces disagree on orientation).
std::string edge_refusal(const TriangleSoup& soup) {
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(soup.triangles.size() * 3);
  for (const Triangle& t : soup.triangles)
    for (int i = 0; i < 3; ++i)
      if (++directed[detail::directed_edge_key(t[i], t[(i + 1) % 3])] > 1)
        return "an edge has more than two faces or its faces disagree on orientation";
  return {};
}

}  // namespace

std::string defects_other_than_holes(const TriangleSoup& welded) {
  if (std::string why = face_refusal(welded); !why.empty()) return why;
  if (std::string why = edge_refusal(welded); !why.empty()) return why;
  if (detail::FilledSurface(welded).meets_itself())
    return "faces meet away from their shared vertices and edges";
  return {};
}

}  // namespace mr::hole_fill
