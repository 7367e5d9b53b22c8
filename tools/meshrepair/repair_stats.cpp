#include "repair_stats.h"
#include "provenance_output.h"

#include <mr/check/distance.h>
#include <mr/check/surface_check.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>

#include <algorithm>
#include <chrono>

namespace mr::tools {
namespace {

nlohmann::json input_defects(const TriangleSoup& input) {
  const check::SurfaceReport r = check::check_surface(input);
  return {{"faces", r.faces},
          {"vertices", r.vertices},
          {"boundary_edges", r.boundary_edges},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"inconsistent_edges", r.inconsistent_edges},
          {"degenerate_faces", r.degenerate_faces},
          {"duplicate_faces", r.duplicate_faces},
          {"self_intersecting_pairs", r.self_intersecting_pairs},
          {"components", r.components}};
}

// The defect faces found before the tets and what cutting them out gave.
nlohmann::json defects_cut_figures(const DefectCut& cut) {
  return {{"faces", cut.faces}, {"defect_faces", cut.defect_faces},
          {"local", cut.local}, {"cut_faces", cut.cut_faces},
          {"rings", cut.rings}, {"declined", cut.declined}};
}

// Genus of a closed surface: components - Euler characteristic / 2.
std::int64_t genus(const check::SurfaceReport& r) {
  const auto v = static_cast<std::int64_t>(r.vertices), f = static_cast<std::int64_t>(r.faces);
  const std::int64_t edges = 3 * f / 2;
  return static_cast<std::int64_t>(r.components) - (v - edges + f) / 2;
}

nlohmann::json output_figures(const TriangleSoup& surface, const TriangleSoup& input) {
  const check::SurfaceReport r = check::check_surface(surface);
  const check::DistanceReport to_input = check::one_sided_distance(surface, input);
  const check::DistanceReport from_input = check::one_sided_distance(input, surface);
  return {{"faces", r.faces},
          {"vertices", r.vertices},
          {"components", r.components},
          {"genus", r.closed() && r.manifold() ? nlohmann::json(genus(r)) : nlohmann::json(nullptr)},
          {"volume", r.volume},
          {"watertight", r.watertight()},
          {"boundary_edges", r.boundary_edges},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"self_intersecting_pairs", r.self_intersecting_pairs},
          {"degenerate_faces", r.degenerate_faces},
          {"hausdorff_output_to_input", to_input.max},
          {"hausdorff_input_to_output", from_input.max},
          {"mean_distance_output_to_input", to_input.mean},
          {"mean_distance_input_to_output", from_input.mean}};
}

// The file as written, read back (float32 or quantized positions).
nlohmann::json written_figures(const check::SurfaceReport& r) {
  return {{"faces", r.faces},
          {"vertices", r.vertices},
          {"watertight", r.watertight()},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"self_intersecting_pairs", r.self_intersecting_pairs},
          {"degenerate_faces", r.degenerate_faces}};
}

nlohmann::json repair_figures(const repair::RepairResult& r) {
  return {{"nonmanifold_edges_found", r.manifold.nonmanifold_edges_found},
          {"nonmanifold_vertices_found", r.manifold.nonmanifold_vertices_found},
          {"collar_splits", r.manifold.collar_splits},
          {"vertex_copies", r.manifold.vertex_copies},
          {"removed_tets", r.manifold.removed_tets},
          {"added_tets", r.manifold.added_tets},
          {"edit_faces_outside_envelope", r.manifold.faces_outside_envelope},
          {"manifold_rounds", r.manifold.rounds},
          {"manifold_fell_back", r.manifold.fell_back},
          {"fallback_added_tets", r.manifold.fallback_added_tets},
          {"peeled_faces", r.peeled_faces},
          {"input_triangles_put_back", r.input_triangles_put_back},
          {"fan_merges_undone", r.fan_merges_undone},
          {"collapses", r.collapses},
          {"flips", r.flips},
          {"output_grid", r.grid.name()},
          {"rounded_vertices", r.rounding.moved},
          {"rounded_off_nearest", r.rounding.nearest_refused},
          {"rounding_sent_back", r.rounding.sent_back},
          {"rounding_collapsed", r.rounding.collapsed},
          {"finer_output_grids", r.finer_grids},
          {"rounding_passes", r.rounding.passes},
          {"rounding_tries", r.rounding.tries},
          {"rounding_max_move", r.rounding.max_move}};
}

// Why the outer hull was rebuilt instead of the input, and its grid (null: it was not).
nlohmann::json hull_figures(const OuterHull* hull) {
  if (!hull) return nullptr;
  return {
      {"reason", hull->reason}, {"voxel_size", hull->voxel_size}, {"faces", hull->surface.triangles.size()}};
}

nlohmann::json stage_seconds(const RepairRun& run) {
  nlohmann::json stages = nlohmann::json::array();
  stages.push_back({{"name", "read"}, {"seconds", run.seconds_read}});
  stages.push_back({{"name", "hole_fill_tried"}, {"seconds", run.seconds_hole_fill_tried}});
  stages.push_back({{"name", "keep_input_abandoned"}, {"seconds", run.keep_input.seconds_abandoned}});
  stages.push_back({{"name", "keep_input_gave_way"}, {"seconds", run.keep_input.seconds_gave_way}});
  if (run.hull) {
    stages.push_back({{"name", "rebuild_too_costly"}, {"seconds", run.hull->seconds_rebuild_tried}});
    stages.push_back({{"name", "outer_hull"}, {"seconds", run.hull->seconds}});
  }
  for (const tetmesh::StageStats& s : run.pipeline.stats.stages) {
    nlohmann::json stage = {{"name", s.name}, {"seconds", s.seconds}};
    for (const auto& [key, value] : s.counts) stage["counts"][key] = value;
    stages.push_back(std::move(stage));
  }
  for (const repair::StageTime& s : run.repair.stages)
    stages.push_back({{"name", s.name}, {"seconds", s.seconds}});
  stages.push_back({{"name", "write"}, {"seconds", run.seconds_write}});
  stages.push_back({{"name", "check_written"}, {"seconds", run.written.seconds}});
  return stages;
}

// Peak memory of the run so far, and per input face (bench/README.md, "Large inputs").
nlohmann::json memory_figures(const TriangleSoup& input) {
  const double peak_mb = cli::peak_memory_mb();
  return {
      {"peak_mb", peak_mb},
      {"bytes_per_input_face", input.triangles.empty() ? 0.0 : peak_mb * 1048576.0 / input.triangles.size()}};
}

}  // namespace

nlohmann::json make_repair_stats(const RepairRun& run) {
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json stats = {
      {"memory", memory_figures(run.input)},
      {"path", run.hull ? "outer_hull" : "tetrahedralize"},
      {"outer_hull", hull_figures(run.hull)},
      {"hole_fill_declined", run.hole_fill_declined},
      {"keep_input_abandoned", run.keep_input.abandoned},
      {"keep_input_band_rings", run.keep_input.band_rings},
      {"keep_input_gave_way", run.keep_input.gave_way},
      {"defects_cut", defects_cut_figures(run.defects_cut)},
      {"input", input_defects(run.input)},
      {"epsilon_abs", run.pipeline.parameters.epsilon},
      {"bbox_diagonal", run.pipeline.parameters.diagonal},
      {"kept_tets", std::count(run.pipeline.mesh.tet_labels.begin(), run.pipeline.mesh.tet_labels.end(), 1)},
      {"repair", repair_figures(run.repair)},
      {"output", output_figures(run.repair.surface, run.input)},
      {"provenance", provenance_figures(run.provenance)},
      {"written_file", written_figures(run.written.surface)},
      {"stages", stage_seconds(run)}};
  stats["seconds_measuring"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

nlohmann::json make_holes_only_stats(const HolesOnlyRun& run) {
  const auto start = std::chrono::steady_clock::now();
  const hole_fill::HoleFillResult& fill = *run.holes.fill;
  std::size_t patch_faces = 0, patch_vertices = 0;
  for (const hole_fill::HoleReport& h : fill.holes)
    patch_faces += h.patch_faces, patch_vertices += h.patch_vertices;
  nlohmann::json stats = {
      {"memory", memory_figures(run.input)},
      {"path", run.holes.defects_cut() ? "cut_and_fill" : "hole_fill"},
      {"input", input_defects(run.input)},
      {"epsilon_abs", run.epsilon},
      {"bbox_diagonal", bounding_box_diagonal(run.input)},
      {"repeated_faces", run.holes.repeated_faces},
      {"flipped_faces", run.holes.flipped_faces},
      {"zero_area_faces",
       {{"taken_out", run.holes.zero_area_dropped}, {"split_faces", run.holes.split_faces}}},
      {"defects_cut", defects_cut_figures(run.holes.cut)},
      {"holes",
       {{"found", fill.holes.size()},
        {"filled", fill.filled()},
        {"kept_input_faces", fill.input_faces - 2 * run.holes.split_faces},  // a split face is two
        {"patch_faces", patch_faces},
        {"patch_vertices", patch_vertices}}},
      {"repair",
       {{"rounded_vertices", run.written.rounding.moved},
        {"rounded_off_nearest", run.written.rounding.nearest_refused},
        {"rounding_sent_back", run.written.rounding.sent_back}}},
      {"output", output_figures(fill.surface, run.input)},
      {"provenance", provenance_figures(run.provenance)},
      {"written_file", written_figures(run.written.written.surface)},
      {"stages",
       nlohmann::json::array({{{"name", "read"}, {"seconds", run.seconds_read}},
                              {{"name", "hole_fill"}, {"seconds", run.seconds_fill}},
                              {{"name", "write"}, {"seconds", run.seconds_write}},
                              {{"name", "check_written"}, {"seconds", run.written.written.seconds}}})}};
  stats["seconds_measuring"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace mr::tools
