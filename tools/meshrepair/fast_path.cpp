#include "fast_path.h"

#include <mr/tetmesh/insertion.h>

#include <chrono>

namespace mr::tools {

tetmesh::TetrahedralizeOptions repair_defaults() {
  tetmesh::TetrahedralizeOptions options;
  options.lattice_spacing_rel = 0.0;
  return options;
}

double epsilon_for(const TriangleSoup& input, const tetmesh::TetrahedralizeOptions& tetrahedralize) {
  return tetrahedralize.epsilon_abs > 0.0 ? tetrahedralize.epsilon_abs
                                          : tetrahedralize.epsilon_rel * bounding_box_diagonal(input);
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

namespace {

tetmesh::PipelineOptions kept_input_options(const tetmesh::TetrahedralizeOptions& tetrahedralize,
                                            int band_rings, std::size_t max_tets,
                                            std::size_t max_rebuild_tets) {
  tetmesh::PipelineOptions pipeline = repair_pipeline_options(tetrahedralize, RebuildMode::keep_input);
  pipeline.tetrahedralize.defect_band_rings = band_rings;
  pipeline.tetrahedralize.max_insertion_tets = max_tets;
  pipeline.tetrahedralize.max_rebuild_insertion_tets = max_rebuild_tets;
  return pipeline;
}

}  // namespace

RepairTets tetrahedralize_for_repair(const TriangleSoup& input,
                                     const tetmesh::TetrahedralizeOptions& tetrahedralize, RebuildMode mode,
                                     const RepairTetsOptions& options) {
  RepairTets tets;
  const std::size_t rebuild_budget = options.keep_or_nothing ? 0 : options.rebuild_budget;
  if (mode == RebuildMode::keep_input) {
    for (std::size_t i = 0; i < kKeepInputBands.size(); ++i) {
      const bool last = i + 1 == kKeepInputBands.size();
      const std::size_t budget = last && options.keep_or_nothing ? 0
                                 : options.tet_budget > 0        ? options.tet_budget
                                                          : keep_input_tet_budget(input.triangles.size());
      const auto start = std::chrono::steady_clock::now();
      try {
        tets.pipeline = tetmesh::tetrahedralize(
            input, kept_input_options(tetrahedralize, kKeepInputBands[i], budget, rebuild_budget),
            options.logger);
        tets.mode = RebuildMode::keep_input;
        tets.band_rings = kKeepInputBands[i];
        return tets;
      } catch (const tetmesh::RebuildTooCostly&) {
        throw;  // the band held every face: the rebuild would run the same insertion
      } catch (const tetmesh::InsertionTooCostly& e) {
        tets.seconds_gave_way +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        tets.gave_way.push_back("band of " + std::to_string(kKeepInputBands[i]) + " rings: " + e.what());
        if (options.on_give_way)
          options.on_give_way(tets.gave_way.back(), last ? "rebuilding the surface instead"
                                                         : "simplifying a band of " +
                                                               std::to_string(kKeepInputBands[i + 1]) +
                                                               " rings around defects instead");
      }
    }
  }
  tetmesh::PipelineOptions rebuild = repair_pipeline_options(tetrahedralize, RebuildMode::remesh);
  rebuild.tetrahedralize.max_rebuild_insertion_tets = rebuild_budget;
  tets.pipeline = tetmesh::tetrahedralize(input, rebuild, options.logger);
  return tets;
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
