#include "holes_only_repair.h"

#include <mr/check/surface_check.h>
#include <mr/core/orientation.h>
#include <mr/core/weld.h>
#include <mr/hole_fill/holes_only.h>
#include <mr/hole_fill/redundant_faces.h>

#include <utility>

namespace mr::tools {

namespace {

// Turns every face, patches included, of a surface whose faces all point inward.
void turn_outward(TriangleSoup& surface, double volume) {
  if (volume < 0)
    for (Triangle& t : surface.triangles) std::swap(t[1], t[2]);
}

// The defects of `cleaned` cut out and the holes filled, into r.fill when
// accepted.
void cut_out(HolesOnlyRepair& r, const TriangleSoup& cleaned, const CoordinateGrid& grid, double epsilon) {
  DefectCutOptions options;
  options.epsilon = epsilon;
  options.grid = grid;
  r.cut = cut_out_defects(cleaned, options);
  if (!r.cut.fill) {
    r.declined += "; cutting them out: " + r.cut.declined;
    return;
  }
  r.declined.clear();
  r.fill = std::move(r.cut.fill);
  r.cut.fill.reset();
  turn_outward(r.fill->surface, r.cut.volume);
}

}  // namespace

HolesOnlyRepair repair_holes_only(const TriangleSoup& input, const CoordinateGrid& grid, double epsilon) {
  HolesOnlyRepair r;
  TriangleSoup welded = weld_identical_vertices(input);
  r.repeated_faces = hole_fill::remove_repeated_faces(welded);
  r.flipped_faces = orient_coherently(welded).flipped;
  hole_fill::ZeroAreaRemoval cleaned = hole_fill::remove_zero_area_faces(std::move(welded));
  r.zero_area_dropped = cleaned.dropped;
  r.split_faces = cleaned.split;
  if (cleaned.surface.triangles.empty()) {
    r.declined = "every face has zero area";
    return r;
  }
  r.declined = hole_fill::defects_other_than_holes(cleaned.surface);
  if (!r.declined.empty()) {
    cut_out(r, cleaned.surface, grid, epsilon);
    return r;
  }
  hole_fill::HoleFillOptions options;
  options.grid = grid;
  options.stop_at_first_failure = true;  // a hole left open declines the path
  hole_fill::HoleFillResult fill = hole_fill::fill_holes(cleaned.surface, options);
  if (fill.filled() < fill.holes.size()) {
    r.declined = "a hole could not be filled";
    return r;
  }
  // Without patches the surface is the one defects_other_than_holes found
  // free of intersections, exactly: no need to look again.
  check::SurfaceCheckOptions check_options;
  check_options.self_intersections = !fill.holes.empty();
  const check::SurfaceReport report = check::check_surface(fill.surface, check_options);
  if (!report.closed() || !report.manifold() || report.inconsistent_edges || report.degenerate_faces ||
      (check_options.self_intersections && report.self_intersecting_pairs != 0)) {
    r.declined = "the filled surface is not watertight: " + check::watertight_failures(report);
    return r;
  }
  turn_outward(fill.surface, report.volume);
  r.fill = std::move(fill);
  return r;
}

}  // namespace mr::tools
