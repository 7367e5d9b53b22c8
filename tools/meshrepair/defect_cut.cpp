#include "defect_cut.h"

#include <mr/check/distance.h>
#include <mr/check/surface_check.h>
#include <mr/core/union_find.h>
#include <mr/spatial/defect_faces.h>
#include <mr/spatial/improper_meetings.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace mr::tools {
namespace {

constexpr Index kUnused = ~Index(0);

// The faces of `soup` whose flag is `flagged`, over the vertices they use
// (positions unchanged, in their order).
TriangleSoup faces_flagged(const TriangleSoup& soup, const std::vector<std::uint8_t>& flags, bool flagged) {
  TriangleSoup part;
  std::vector<Index> index(soup.positions.size(), kUnused);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    if (bool(flags[f]) == flagged)
      for (Index v : soup.triangles[f]) index[v] = 0;
  for (std::size_t v = 0; v < index.size(); ++v)
    if (index[v] != kUnused) {
      index[v] = static_cast<Index>(part.positions.size());
      part.positions.push_back(soup.positions[v]);
    }
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    if (bool(flags[f]) == flagged) {
      const Triangle& t = soup.triangles[f];
      part.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
    }
  return part;
}

TriangleSoup patch_faces(const hole_fill::HoleFillResult& fill) {
  TriangleSoup patches;
  patches.positions = fill.surface.positions;
  patches.triangles.assign(fill.surface.triangles.begin() + static_cast<std::ptrdiff_t>(fill.input_faces),
                           fill.surface.triangles.end());
  return patches;
}

// Why the surface `fill` made from `welded` less `cut` is refused, or an
// empty string when it is accepted (its signed volume then in `volume`).
std::string refusal(const hole_fill::HoleFillResult& fill, const TriangleSoup& welded,
                    const TriangleSoup& cut, double epsilon, double& volume) {
  if (fill.filled() < fill.holes.size() || fill.open_border_edges != 0) return "a hole could not be filled";
  // The sampled distances first: they refuse most bands, for less than the
  // exact check costs.
  if (!check::lies_within(patch_faces(fill), welded, epsilon)) return "a patch leaves the input's epsilon";
  if (!check::lies_within(cut, fill.surface, epsilon))
    return "a face cut out is farther than epsilon from the patches";
  check::SurfaceReport report = check::check_surface(fill.surface);
  volume = report.volume;
  report.volume = std::abs(report.volume);  // the caller turns an inward surface
  if (!report.watertight())
    return "the filled surface is not watertight: " + check::watertight_failures(report);
  return {};
}

// Whether a defect face meets a face of another part (parts: faces joined
// through shared vertices). Cut out and filled, each part closes on its own
// and still overlaps the other; their union needs the tets.
bool parts_cross(const TriangleSoup& welded, const std::vector<std::uint8_t>& defects) {
  UnionFind parts(welded.positions.size());
  for (const Triangle& t : welded.triangles) parts.unite(t[0], t[1]), parts.unite(t[1], t[2]);
  std::vector<std::uint32_t> part(welded.triangles.size());
  for (std::size_t f = 0; f < part.size(); ++f)
    part[f] = static_cast<std::uint32_t>(parts.find(welded.triangles[f][0]));
  const std::vector<std::uint8_t> meets = spatial::faces_meeting_others(welded, defects, {}, part);
  return std::find(meets.begin(), meets.end(), 1) != meets.end();
}

// The most faces a band may cut before wider ones are given up.
std::size_t max_cut_faces(const DefectCutOptions& options, std::size_t faces) {
  return std::max(options.min_cut_faces,
                  static_cast<std::size_t>(options.max_cut_share * static_cast<double>(faces)));
}

// The faces flagged in `cut_flags` (`cut`: the defects and `rings` vertex
// rings around them) taken out of `welded` and the holes filled, into
// result when accepted; true when it was.
bool try_band(const TriangleSoup& welded, int rings, const TriangleSoup& cut,
              const std::vector<std::uint8_t>& cut_flags, const DefectCutOptions& options,
              DefectCut& result) {
  hole_fill::HoleFillOptions fill_options;
  fill_options.grid = options.grid;
  fill_options.stop_at_first_failure = true;  // a band with a hole left open is refused
  hole_fill::HoleFillResult fill =
      hole_fill::fill_holes(faces_flagged(welded, cut_flags, false), fill_options);
  const std::string why = refusal(fill, welded, cut, options.epsilon, result.volume);
  if (!why.empty()) {
    result.declined = "band of " + std::to_string(rings) + " rings: " + why;
    return false;
  }
  result.declined.clear();
  result.rings = rings;
  result.cut_faces = cut.triangles.size();
  result.fill = std::move(fill);
  return true;
}

}  // namespace

DefectCut cut_out_defects(const TriangleSoup& welded, const DefectCutOptions& options) {
  DefectCut result;
  const std::vector<std::uint8_t> defects = spatial::defect_faces(welded);
  result.defect_faces = static_cast<std::size_t>(std::count(defects.begin(), defects.end(), 1));
  const std::size_t faces = welded.triangles.size();
  result.faces = faces;
  result.local = result.defect_faces <= options.max_defect_share * static_cast<double>(faces);
  if (!result.local) {
    result.declined = "defects are not local: " + std::to_string(result.defect_faces) + " of " +
                      std::to_string(faces) + " faces";
    return result;
  }
  if (parts_cross(welded, defects)) {
    result.declined = "parts cross each other";
    return result;
  }
  for (int rings : options.rings) {
    std::vector<std::uint8_t> cut_flags = defects;
    spatial::grow_by_vertex_rings(welded, rings, cut_flags);
    const TriangleSoup cut = faces_flagged(welded, cut_flags, true);
    if (cut.triangles.size() > max_cut_faces(options, faces)) {
      result.declined += (result.declined.empty() ? "" : "; ") + std::string("a band of ") +
                         std::to_string(rings) + " rings cuts " + std::to_string(cut.triangles.size()) +
                         " faces, more than " + std::to_string(max_cut_faces(options, faces));
      return result;
    }
    if (try_band(welded, rings, cut, cut_flags, options, result)) return result;
  }
  return result;
}

}  // namespace mr::tools
