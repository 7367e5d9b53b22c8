#include "fast_path.h"

namespace mr::tools {

tetmesh::TetrahedralizeOptions repair_defaults() {
  tetmesh::TetrahedralizeOptions options;
  options.lattice_spacing_rel = 0.0;
  return options;
}

RebuildMode rebuild_mode(std::size_t faces, std::optional<RebuildMode> requested) {
  if (requested) return *requested;
  return faces <= kKeepInputMaxFaces ? RebuildMode::keep_input : RebuildMode::remesh;
}

tetmesh::PipelineOptions repair_pipeline_options(const tetmesh::TetrahedralizeOptions& tetrahedralize,
                                                 RebuildMode mode) {
  tetmesh::PipelineOptions options;
  options.tetrahedralize = tetrahedralize;
  if (mode == RebuildMode::keep_input) options.tetrahedralize.simplify_near_defects_only = true;
  options.tetrahedralize.winding_rule = tetmesh::WindingRule::absolute;
  options.filter = true;
  options.keep_rejected = true;
  options.improve = false;
  return options;
}

repair::RepairOptions surface_repair_options(const tetmesh::PipelineResult& pipeline, int threads,
                                             bool cleanup, RebuildMode mode) {
  repair::RepairOptions options;
  options.keep_input_triangles = mode == RebuildMode::keep_input;
  options.inserted_input = &pipeline.inserted_surface;
  options.inserted_snap_spacing = pipeline.snap_spacing;
  options.epsilon = pipeline.parameters.epsilon;
  options.threads = threads;
  options.cleanup = cleanup;
  return options;
}

std::vector<std::uint8_t> inside_labels(const tetmesh::PipelineResult& pipeline) {
  return {pipeline.mesh.tet_labels.begin(), pipeline.mesh.tet_labels.end()};
}

}  // namespace mr::tools
