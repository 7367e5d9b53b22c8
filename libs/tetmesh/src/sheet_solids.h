#pragma once
// An input that encloses no volume (sheets only, or every face doubled with
// both orientations) leaves the filter nothing to keep. These are the
// solids the pipeline meshes instead: the sheets thickened, then fattened,
// or the grid cells a tiny input meets, each within epsilon of the input.

#include <mr/tetmesh/tetrahedralize.h>

#include <functional>

namespace mr::tetmesh::detail {

/// One run of the pipeline; `stats` carries the stages of an earlier run.
using PipelineRun =
    std::function<PipelineResult(const TriangleSoup&, const PipelineOptions&, PipelineStats, const Logger&)>;

/// `result` (a run on `input`) if it kept some tets; otherwise the run on
/// the first of the solids above that keeps some, its tets valid but not
/// improved, its epsilon measured from the input.
PipelineResult solid_where_nothing_kept(const TriangleSoup& input, const PipelineOptions& options,
                                        PipelineResult result, const PipelineRun& run, const Logger& logger);

}  // namespace mr::tetmesh::detail
