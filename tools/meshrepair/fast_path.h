#pragma once
// The settings of meshrepair's rebuild through tets, shared by the tool and
// the Python module so the two cannot drift apart.

#include <mr/repair/repair.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mr::tools {

/// The fast path needs a valid embedding, not well-shaped interior tets, so
/// its background mesh has no voxel lattice: lattice points make every input
/// triangle cross many more tets (docs/ARCHITECTURE.md, "Repair").
tetmesh::TetrahedralizeOptions repair_defaults();

/// The envelope radius the pipeline uses for `input`.
double epsilon_for(const TriangleSoup& input, const tetmesh::TetrahedralizeOptions& tetrahedralize);

/// How much of the input the rebuild keeps.
enum class RebuildMode {
  /// Input triangles away from defects come out as they went in: only the
  /// faces near defects are simplified before insertion, so that the peeled
  /// faces tile the others' (snapped) triangles, which go back with their
  /// own corners.
  keep_input,
  /// The whole surface rebuilt and simplified inside the envelope.
  remesh,
};

/// Inputs up to this many faces keep their triangles by default; larger
/// ones are rebuilt (--keep-input asks for it at any size): inserting a big
/// input unsimplified costs minutes (docs/ARCHITECTURE.md, "Keeping the input").
inline constexpr std::size_t kKeepInputMaxFaces = 50'000;

/// The tets keeping an input of `faces` faces may grow insertion to before
/// meshrepair rebuilds it instead: 64 per face, plus room for small inputs.
/// trimesh/Duck needs 4, CesiumMilkTruck 20, mode5 51; trimesh/boolean
/// (202, every face near an intersection) and the CAD slivers of
/// Generic_Twin (6.1M tets after 160 of its 19,670 triangles) are rebuilt.
inline std::size_t keep_input_tet_budget(std::size_t faces) { return 64 * faces + 100'000; }

/// The tets rebuilding every face of an input of `faces` faces may grow
/// insertion to before meshrepair takes the outer hull instead: beyond
/// that, insertion and the stages after it take minutes and gigabytes
/// (manifold/Offset1 with every vertex jittered by epsilon/2: 3.3M tets,
/// 215 s). The hull gives up being within epsilon, so the budget leaves
/// room for inputs that take long but finish: trimesh/cycloidal (43,368
/// faces, 4.0M tets, 216 s) stays exact; with 16 tets a face it went to
/// the hull, 11 epsilons off, in 124 s. 1.5M tets sent trimesh/boolean's
/// jittered and overlapping members (1.6M, 1.7M tets, 25 and 29 s exact)
/// to the hull in 47 and 39 s: reaching the budget is most of its cost.
inline std::size_t rebuild_tet_budget(std::size_t faces) { return 2'000'000 + 64 * faces; }

/// Vertex rings around defects that keeping the input simplifies before
/// insertion, narrowest first. The narrowest keeps every triangle that is not
/// itself a defect; where its insertion grows past the tet budget (long
/// unsimplified faces crossing near the defects, as on trimesh/chair_model
/// and mode5), the wider band hands insertion simplified faces there and
/// usually fits.
inline constexpr std::array<int, 2> kKeepInputBands{0, 2};

/// The mode for an input of `faces` faces: `requested` when set (--remesh,
/// --keep-input), else keep_input up to kKeepInputMaxFaces.
RebuildMode rebuild_mode(std::size_t faces, std::optional<RebuildMode> requested);

/// The tetrahedralization meshrepair runs: filtered by |winding number| > 1/2
/// (a solid whose faces all point inward is repaired too; the peeled surface is
/// oriented by the tets, so it comes out outward), rejected tets kept for the
/// manifold fix, no quality improvement.
tetmesh::PipelineOptions repair_pipeline_options(const tetmesh::TetrahedralizeOptions& tetrahedralize,
                                                 RebuildMode mode);

/// How tetrahedralize_for_repair runs.
struct RepairTetsOptions {
  /// --keep-input: the widest band runs without a tet budget, and the input
  /// is kept or the run fails; never rebuilt instead.
  bool keep_or_nothing = false;
  /// Tets a band's insertion may grow to (0: keep_input_tet_budget of the input).
  std::size_t tet_budget = 0;
  /// Tets rebuilding every face may grow insertion to before it throws
  /// tetmesh::RebuildTooCostly (0: no limit). keep_or_nothing lifts it.
  std::size_t rebuild_budget = 0;
  tetmesh::Logger logger;
  /// Told, as it happens, why a band gave way and what comes next (may be empty).
  std::function<void(const std::string& why, const std::string& next)> on_give_way;
};

/// The tets of meshrepair's rebuild and how they were reached.
struct RepairTets {
  tetmesh::PipelineResult pipeline;
  RebuildMode mode = RebuildMode::remesh;  ///< remesh where keeping the input was given up
  int band_rings = -1;                     ///< the defect band the input was kept with (-1: rebuilt)
  std::vector<std::string> gave_way;       ///< why each band that gave way did, in order
  double seconds_gave_way = 0.0;           ///< what the bands that gave way cost
};

/// The pipeline in `mode`. Keeping the input tries the bands of
/// kKeepInputBands in turn, each within keep_input_tet_budget, and gives way
/// to rebuilding (mode remesh) when none fits, unless keep_or_nothing.
/// Throws tetmesh::RebuildTooCostly past options.rebuild_budget.
RepairTets tetrahedralize_for_repair(const TriangleSoup& input,
                                     const tetmesh::TetrahedralizeOptions& tetrahedralize, RebuildMode mode,
                                     const RepairTetsOptions& options);

/// The surface repair's options for a pipeline's result (which must outlive
/// them); the output grids are the caller's.
repair::RepairOptions surface_repair_options(const tetmesh::PipelineResult& pipeline, int threads,
                                             bool cleanup, RebuildMode mode);

/// The tet labels as the surface repair takes them (1 = inside).
std::vector<std::uint8_t> inside_labels(const tetmesh::PipelineResult& pipeline);

}  // namespace mr::tools
