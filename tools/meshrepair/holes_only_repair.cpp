#include "holes_only_repair.h"

#include <mr/check/surface_check.h>
#include <mr/hole_fill/holes_only.h>

#include <utility>

namespace mr::tools {

HolesOnlyRepair repair_holes_only(const TriangleSoup& input, const CoordinateGrid& grid) {
  HolesOnlyRepair r;
  r.declined = hole_fill::defects_other_than_holes(input, /*accept_closed=*/true);
  if (!r.declined.empty()) return r;
  hole_fill::HoleFillOptions options;
  options.grid = grid;
  hole_fill::HoleFillResult fill = hole_fill::fill_holes(input, options);
  if (fill.filled() < fill.holes.size()) {
    r.declined = "a hole could not be filled";
    return r;
  }
  const check::SurfaceReport report = check::check_surface(fill.surface);
  if (!report.closed() || !report.manifold() || report.inconsistent_edges || report.degenerate_faces ||
      report.self_intersecting_pairs != 0) {
    r.declined = "the filled surface is not watertight: " + check::watertight_failures(report);
    return r;
  }
  if (report.volume < 0)  // an inward input: turn every face, patches included
    for (Triangle& t : fill.surface.triangles) std::swap(t[1], t[2]);
  r.fill = std::move(fill);
  return r;
}

}  // namespace mr::tools
