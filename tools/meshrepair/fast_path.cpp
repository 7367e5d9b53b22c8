#include "fast_path.h"

namespace mr::tools {

tetmesh::TetrahedralizeOptions repair_defaults() {
  tetmesh::TetrahedralizeOptions options;
  options.lattice_spacing_rel = 0.0;
  return options;
}

tetmesh::PipelineOptions repair_pipeline_options(const tetmesh::TetrahedralizeOptions& tetrahedralize) {
  tetmesh::PipelineOptions options;
  options.tetrahedralize = tetrahedralize;
  options.tetrahedralize.winding_rule = tetmesh::WindingRule::absolute;
  options.filter = true;
  options.keep_rejected = true;
  options.improve = false;
  return options;
}

repair::RepairOptions surface_repair_options(const tetmesh::PipelineResult& pipeline, int threads,
                                             bool cleanup) {
  repair::RepairOptions options;
  options.epsilon = pipeline.parameters.epsilon;
  options.threads = threads;
  options.cleanup = cleanup;
  return options;
}

std::vector<std::uint8_t> inside_labels(const tetmesh::PipelineResult& pipeline) {
  return {pipeline.mesh.tet_labels.begin(), pipeline.mesh.tet_labels.end()};
}

}  // namespace mr::tools
