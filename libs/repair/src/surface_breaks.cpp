#include "surface_breaks.h"

#include <mr/kernel/predicates.h>
#include <mr/spatial/improper_meetings.h>

#include <unordered_map>

namespace mr::repair {

std::vector<std::uint8_t> vertices_breaking_surface(const TriangleSoup& surface,
                                                    std::span<const std::uint8_t> moved) {
  const std::size_t faces = surface.triangles.size();
  std::vector<std::uint8_t> asked(faces, 0), breaks(faces, 0);
  for (std::size_t f = 0; f < faces; ++f) {
    const Triangle& t = surface.triangles[f];
    asked[f] = moved[t[0]] || moved[t[1]] || moved[t[2]];
    if (!asked[f]) continue;
    const std::array<Vec3d, 3> p = surface.corners(f);
    breaks[f] = collinear(p[0], p[1], p[2]);
  }
  const std::vector<std::uint8_t> meets = spatial::faces_meeting_others(surface, asked);
  std::vector<std::uint8_t> back(surface.positions.size(), 0);
  for (std::size_t f = 0; f < faces; ++f)
    if (breaks[f] || meets[f])
      for (Index v : surface.triangles[f]) back[v] = moved[v];
  std::unordered_map<Vec3d, Index, PositionHash, PositionEqual> first_at;
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    const auto [it, inserted] = first_at.emplace(surface.positions[v], static_cast<Index>(v));
    if (inserted) continue;
    back[v] = moved[v];
    back[it->second] = moved[it->second];
  }
  return back;
}

}  // namespace mr::repair
