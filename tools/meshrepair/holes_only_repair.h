#pragma once
// meshrepair's first path: an input whose only defects are holes gets them
// closed by hole-fill's patches, every input face kept, instead of being
// rebuilt by the tetrahedral pipeline; one whose other defects are few and
// local gets them cut out and the holes left filled (defect_cut.h).

#include <mr/core/coordinate_grid.h>
#include <mr/hole_fill/hole_fill.h>

#include "defect_cut.h"

#include <optional>
#include <string>

namespace mr::tools {

struct HolesOnlyRepair {
  std::string declined;                           ///< why the path was not taken; empty when it was
  std::optional<hole_fill::HoleFillResult> fill;  ///< set when it was: a watertight surface, outward
  std::size_t zero_area_dropped = 0;              ///< zero-area input faces taken out first
  std::size_t split_faces = 0;     ///< input faces split where a collinear face lay on their edge
  std::size_t repeated_faces = 0;  ///< copies of an earlier input face (either way round) dropped
  std::size_t flipped_faces = 0;   ///< input faces turned to agree with their neighbours
  /// Defects other than holes cut out (cut.fill moved to fill when accepted;
  /// cut.declined says why not otherwise).
  DefectCut cut;
  bool defects_cut() const { return cut.rings >= 0; }
};

/// Fills the holes of `input` when they are all it lacks (hole_fill::
/// defects_other_than_holes) once its copies of a face and its zero-area
/// faces are taken out (hole_fill/redundant_faces.h: nothing moves) and its faces turned to
/// agree with their neighbours (orient_coherently), new vertices on `grid`; a watertight input
/// passes as it is, at any size (checking it costs seconds where rebuilding
/// a large one costs more and changes every face). Where it has other
/// defects, tries cutting them out within `epsilon` (cut_out_defects).
/// Declines when neither gives a surface closed, manifold and free of
/// self-intersections.
HolesOnlyRepair repair_holes_only(const TriangleSoup& input, const CoordinateGrid& grid, double epsilon);

}  // namespace mr::tools
