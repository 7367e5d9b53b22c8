#include <mr/spatial/defect_faces.h>

#include <mr/core/weld.h>
#include <mr/kernel/predicates.h>
#include <mr/spatial/improper_meetings.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>

namespace mr::spatial {
namespace {

void flag_degenerate(const TriangleSoup& welded, std::vector<std::uint8_t>& flags) {
  for (std::size_t f = 0; f < welded.triangles.size(); ++f) {
    const Triangle& t = welded.triangles[f];
    const std::array<Vec3d, 3> p = welded.corners(f);
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || collinear(p[0], p[1], p[2])) flags[f] = 1;
  }
}

// Edges of other than two faces, or whose two faces run it the same way.
void flag_bad_edges(const TriangleSoup& welded, std::vector<std::uint8_t>& flags) {
  std::map<std::pair<Index, Index>, std::vector<std::pair<std::size_t, bool>>> edges;
  for (std::size_t f = 0; f < welded.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const Index a = welded.triangles[f][i], b = welded.triangles[f][(i + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(f, a < b);
    }
  for (const auto& [edge, faces] : edges)
    if (faces.size() != 2 || faces[0].second == faces[1].second)
      for (const auto& [f, forward] : faces) flags[f] = 1;
}

void flag_intersecting(const TriangleSoup& welded, std::vector<std::uint8_t>& flags) {
  const std::vector<std::uint8_t> degenerate = flags;  // no triangle to test or to test against
  const std::vector<std::uint8_t> meets = faces_meeting_others(welded, {}, degenerate);
  for (std::size_t f = 0; f < meets.size(); ++f) flags[f] |= meets[f];
}

}  // namespace

std::vector<std::uint8_t> defect_faces(const TriangleSoup& welded) {
  std::vector<std::uint8_t> flags(welded.triangles.size(), 0);
  flag_degenerate(welded, flags);
  flag_intersecting(welded, flags);  // before any other flag: it skips the degenerate faces
  flag_bad_edges(welded, flags);
  return flags;
}

void grow_by_vertex_rings(const TriangleSoup& welded, int rings, std::vector<std::uint8_t>& flags) {
  std::vector<std::uint8_t> vertex(welded.positions.size());
  for (int ring = 0; ring < rings; ++ring) {
    std::fill(vertex.begin(), vertex.end(), std::uint8_t(0));
    for (std::size_t f = 0; f < flags.size(); ++f)
      if (flags[f])
        for (Index v : welded.triangles[f]) vertex[v] = 1;
    for (std::size_t f = 0; f < flags.size(); ++f)
      for (Index v : welded.triangles[f]) flags[f] |= vertex[v];
  }
}

std::vector<std::uint8_t> faces_near_defects(const TriangleSoup& soup, int rings) {
  const TriangleSoup welded = weld_identical_vertices(soup);
  std::vector<std::uint8_t> flags = defect_faces(welded);
  grow_by_vertex_rings(welded, rings, flags);
  return flags;
}

}  // namespace mr::spatial
