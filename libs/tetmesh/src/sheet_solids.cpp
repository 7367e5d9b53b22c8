// The solids made of an input that encloses no volume, for the pipeline to
// mesh instead (tetrahedralize.cpp runs it; see sheet_solids.h).

#include "sheet_solids.h"

#include <mr/core/thicken.h>

#include <algorithm>
#include <utility>

namespace mr::tetmesh::detail {
namespace {

bool kept_some(const PipelineResult& result) {
  const auto& labels = result.mesh.tet_labels;
  return std::find(labels.begin(), labels.end(), 1) != labels.end();
}

/// How a solid is made of an input that encloses no volume.
struct SheetSolid {
  const char* message;
  const char* counter;  ///< the filter stage's count that says it was used
  TriangleSoup (*make)(const TriangleSoup&, double);
  double radius;   ///< of the pieces, in epsilons of the input
  double epsilon;  ///< of the run on the pieces, in epsilons of the input
};

// An input that encloses no volume (sheets only, or every face doubled
// with both orientations) leaves nothing to keep. Its sheets are then given
// a thickness of epsilon and the pipeline runs again with half the epsilon:
// the prisms are within epsilon/2 of the input and the result within
// epsilon/2 of the prisms.
constexpr SheetSolid kThickened{"the input encloses no volume: meshing its sheets thickened to epsilon",
                                "thickened_sheets", thicken_sheets, 0.5, 0.5};
// Prisms vanish where the input is thinner than epsilon in their plane too
// (slivers; a whole input far smaller than its epsilon, which a far vertex
// made large): simplification flattens them, snapping merges their corners.
// Fattened pieces are at least epsilon/2 wide in every direction, and the
// run on them uses epsilon/8, which can flatten nothing that wide: within
// 5/16 sqrt(3) + 1/8 < 0.67 epsilon of the input.
constexpr SheetSolid kFattened{
    "the thickened sheets enclose no volume either: meshing them fattened to epsilon/4", "fattened_sheets",
    fatten_sheets, 0.25, 0.125};

// An input a few epsilons across (an unused far vertex set its box, or an
// absolute epsilon larger than the input) makes prisms taller than wide,
// needles crossing each other (a 9-face fuzzer input: 2,949 cut points, 20 s
// in the sanitizer build). The grid cells epsilon/4 wide that it meets (at
// most 16 a side) are within sqrt(3)/4 epsilon of it, and the run on them
// uses epsilon/10, which cannot flatten a cell: within 0.54 epsilon.
constexpr SheetSolid kCells{
    "the input encloses no volume and is a few epsilons across: meshing the cells it meets", "cell_solid",
    cell_solid, 0.25, 0.1};
constexpr double kMaxCellsASide = 16;

// The tets are valid but not improved (see below).
PipelineResult solid_from_sheets(const TriangleSoup& input, const PipelineOptions& options,
                                 const SheetSolid& how, PipelineResult empty, const PipelineRun& run,
                                 const Logger& logger) {
  const DerivedParameters derived = empty.parameters;
  logger.log(LogLevel::warning, how.message);
  PipelineOptions thick = options;
  thick.tetrahedralize.epsilon_abs = how.epsilon * derived.epsilon;
  thick.tetrahedralize.edge_length_abs = derived.edge_length;
  // No lattice: the pieces' box, from which it would be sized, can be far
  // smaller than the input's (a far unused vertex made that), and without
  // improvement a lattice does not help.
  thick.tetrahedralize.lattice_spacing_rel = 0.0;
  // Improvement moves surface vertices by up to the run's epsilon, enough to
  // turn the faces of walls that thin over; the filter orients tracked
  // faces by geometry, so the shell would leak. The fast path's embedding
  // keeps them where insertion put them.
  thick.improve = false;
  empty.stats.stage("filter").count(how.counter, 1);
  PipelineResult result =
      run(how.make(input, how.radius * derived.epsilon), thick, std::move(empty.stats), logger);
  result.parameters.epsilon = derived.epsilon;  // what the result is within, measured from the input
  return result;
}

}  // namespace

PipelineResult solid_where_nothing_kept(const TriangleSoup& input, const PipelineOptions& options,
                                        PipelineResult result, const PipelineRun& run, const Logger& logger) {
  if (kept_some(result)) return result;
  const double cell = kCells.radius * result.parameters.epsilon;
  if (used_bounding_box(input).sizes().maxCoeff() <= kMaxCellsASide * cell)
    return solid_from_sheets(input, options, kCells, std::move(result), run, logger);
  result = solid_from_sheets(input, options, kThickened, std::move(result), run, logger);
  if (kept_some(result)) return result;
  return solid_from_sheets(input, options, kFattened, std::move(result), run, logger);
}

}  // namespace mr::tetmesh::detail
