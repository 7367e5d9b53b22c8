#include "meshrepair.h"
#include "fast_path.h"
#include "holes_only_repair.h"
#include "memory_budget.h"
#include "outer_hull_path.h"
#include "provenance_output.h"
#include "repair_stats.h"
#include "surface_input.h"
#include "surface_output.h"

#include <mr/check/provenance.h>
#include <mr/check/written_file.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/attribute_transfer.h>
#include <mr/repair/repair.h>
#include <mr/tetmesh/insertion.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  tetmesh::TetrahedralizeOptions tetrahedralize = repair_defaults();
  io::WriteOptions write;
  std::optional<int> draco_position_bits;  ///< unset: chosen from epsilon
  bool cleanup = true;
  std::optional<RebuildMode> rebuild;         ///< --remesh, --keep-input; unset: by the input's size
  std::optional<std::size_t> rebuild_budget;  ///< --max-tets; unset: rebuild_tet_budget of the input
  std::string stats_path;
  std::string provenance_path;
  bool source_faces = false;  ///< --source-faces
  std::size_t max_memory = cli::default_max_memory();
  bool quiet = false;
  bool verbose = false;
};

cli::ToolSpec make_spec(ToolOptions& o) {
  using cli::parse_double;
  cli::ToolSpec spec;
  spec.name = "meshrepair";
  spec.summary = "Turn any triangle surface into a watertight one.";
  spec.positionals = {"IN", "OUT"};
  spec.description =
      "The output is closed, edge- and vertex-manifold, oriented outward, free of self-intersections\n"
      "and zero-area faces, and within epsilon of the input wherever the input had surface (holes\n"
      "and gaps are filled). Fast path of the tetrahedralization: background mesh, exact insertion\n"
      "of the input, winding-number filter; then the boundary of the kept tets is made manifold by\n"
      "splitting vertices apart inside the solid (never leaving coincident vertices), peeled, and\n"
      "cleaned up by collapses and flips inside the envelope of the original input. Input triangles\n"
      "away from defects come out as they went in (their corners bit for bit) on inputs of up to 50,000\n"
      "faces, larger ones are rebuilt and simplified (--keep-input, --remesh choose). A watertight input\n"
      "comes out as it is, and one whose only defects are holes keeps every face, at any size: its holes\n"
      "are closed by faired patches (hole-fill).";
  auto& t = o.tetrahedralize;
  spec.options = {
      {"--epsilon", "-e", "EPS", "envelope radius relative to the bbox diagonal (default 1e-3)",
       [&](const std::string& v) { t.epsilon_rel = parse_double("--epsilon", v); }},
      {"--epsilon-abs", "", "EPS", "absolute envelope radius (overrides --epsilon)",
       [&](const std::string& v) { t.epsilon_abs = parse_double("--epsilon-abs", v); }},
      {"--lattice", "", "H",
       "voxel-stuffing lattice spacing of the background mesh relative to the bbox diagonal (default 0: "
       "none)",
       [&](const std::string& v) { t.lattice_spacing_rel = cli::parse_double("--lattice", v); }},
      {"--snap", "", "F",
       "snap the input to a grid of F times epsilon (a power of two at most) before inserting it, and "
       "move cut points closer than that to a later triangle's plane onto it "
       "(default 1e-3, at most 0.01; 0: insert the coordinates as they are)",
       [&](const std::string& v) { t.snap_fraction = cli::parse_double("--snap", v); }},
      {"--skip-simplify", "", "",
       "with --remesh, insert the input as it is, without simplifying it inside the envelope first (without "
       "--remesh it never is)",
       [&](const std::string&) { t.skip_simplify = true; }},
      {"--remesh", "", "",
       "rebuild the whole surface and simplify it inside the envelope (by default input triangles away "
       "from defects are kept as they are on inputs of up to 50,000 faces, and a watertight input, or one "
       "whose only defects are holes, keeps every face)",
       [&](const std::string&) { o.rebuild = RebuildMode::remesh; }},
      {"--keep-input", "", "",
       "keep the input triangles away from defects at any size (by default only up to 50,000 faces: above, "
       "inserting them unsimplified can take many minutes)",
       [&](const std::string&) { o.rebuild = RebuildMode::keep_input; }},
      {"--max-tets", "", "N",
       "tets inserting the rebuilt surface may make before meshrepair rebuilds the outer hull of the input "
       "on a voxel grid instead, a few epsilons from it (default 2,000,000 plus 64 per input face; 0: never)",
       [&](const std::string& v) {
         o.rebuild_budget = cli::parse_int("--max-tets", v, 0, std::numeric_limits<int>::max());
       }},
      {"--no-cleanup", "", "", "keep the peeled surface as it is (no collapses or flips)",
       [&](const std::string&) { o.cleanup = false; }},
      {"--draco", "", "", "compress GLB/glTF output with KHR_draco_mesh_compression (.drc is always Draco)",
       [&](const std::string&) { o.write.draco.compress_gltf = true; }},
      {"--draco-position-bits", "", "N",
       "Draco position quantization bits (default: a grid step of at most epsilon/64, 12 to 30 bits)",
       [&](const std::string& v) {
         o.draco_position_bits = cli::parse_int("--draco-position-bits", v, 1, 30);
       }},
      {"--provenance", "", "FILE",
       "write, as JSON, the input triangle each output face keeps or lies on (-1: filled where the input "
       "had no surface), in the output's face order (not with Draco output, which reorders faces)",
       [&](const std::string& v) { o.provenance_path = v; }},
      {"--source-faces", "", "",
       "store each output face's input triangle in a glTF output as the _SOURCE_FACE vertex attribute "
       "(-1: filled); every face then has vertices of its own (not with Draco)",
       [&](const std::string&) { o.source_faces = true; }},
      cli::ascii_option(o.write.binary),
      cli::stats_option(o.stats_path,
                        "write input defects, output figures (faces, genus, volume, Hausdorff distances both "
                        "ways) and seconds per stage as JSON"),
      cli::threads_option(t.threads),
      cli::max_memory_option(o.max_memory),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose, "also print each stage as it starts and ends"),
  };
  return spec;
}

tetmesh::Logger make_logger(const ToolOptions& o, std::ostream& err) {
  tetmesh::Logger logger;
  if (o.quiet) return logger;
  logger.on_message = [&err, verbose = o.verbose](tetmesh::LogLevel level, std::string_view text) {
    if (level != tetmesh::LogLevel::debug || verbose) err << "meshrepair: " << text << "\n";
  };
  return logger;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The grid the output file stores positions on, for a surface inside [lo, hi];
// Draco's bits are chosen here (the writer is told the grid the surface was
// rounded onto afterwards: write_on_grid).
std::function<CoordinateGrid(const Vec3d&, const Vec3d&)> output_grid(const io::Registry& registry,
                                                                      const std::string& path, double epsilon,
                                                                      const ToolOptions& options,
                                                                      io::WriteOptions& write) {
  return [&registry, path, epsilon, &options, &write](const Vec3d& lo, const Vec3d& hi) {
    write.draco.position_bits =
        options.draco_position_bits.value_or(draco_position_bits_for((hi - lo).maxCoeff(), epsilon));
    return io::surface_position_grid(registry, path, write, lo, hi);
  };
}

// Two more Draco bits when no place on the grid is left for some vertex, if
// meshrepair chose the bits (not --draco-position-bits), up to 24.
std::function<std::optional<CoordinateGrid>(const Vec3d&, const Vec3d&, const CoordinateGrid&)>
finer_output_grid(const io::Registry& registry, const std::string& path, const ToolOptions& options,
                  const io::WriteOptions& write) {
  return [&registry, path, &options, &write](const Vec3d& lo, const Vec3d& hi,
                                             const CoordinateGrid& refused) -> std::optional<CoordinateGrid> {
    if (options.draco_position_bits) return std::nullopt;
    return finer_draco_grid(registry, path, write, lo, hi, refused);
  };
}

// Where each output face came from, measured on the surface as rounded for
// writing: the written file carries the input's attributes by it, the
// --provenance file lists it, --stats and the summary line sum it up.
struct OutputProvenance {
  check::FaceProvenance faces;
  check::ProvenanceSummary summary;
};

// The faces are ordered by region, as the glTF writer writes them, so that
// the --provenance file follows the written file's faces.
TriangleSoup dressed(const TriangleSoup& rounded, const CoordinateGrid& grid, const TriangleSoup& input,
                     double epsilon, bool source_faces, OutputProvenance& provenance) {
  provenance.faces = check::face_provenance(rounded, input, grid, epsilon);
  provenance.summary = check::summarize_provenance(provenance.faces, rounded);
  TriangleSoup surface = repair::with_input_attributes(rounded, input, provenance.faces.input_face, grid);
  order_faces_by_region(surface, provenance.faces);
  if (source_faces) surface.face_sources = provenance.faces.input_face;
  return surface;
}

void write_provenance(const ToolOptions& options, const OutputProvenance& provenance) {
  if (!options.provenance_path.empty()) write_provenance_file(options.provenance_path, provenance.faces);
}

// Draco reorders faces, so a face-order provenance would not match the file;
// _SOURCE_FACE is a glTF attribute.
void check_provenance_request(const ToolOptions& options, const io::Registry& registry,
                              const std::string& out) {
  if (options.provenance_path.empty() && !options.source_faces) return;
  const CoordinateGrid grid =
      io::surface_position_grid(registry, out, options.write, Vec3d::Zero(), Vec3d::Ones());
  const char* option = options.provenance_path.empty() ? "--source-faces: " : "--provenance: ";
  if (grid.kind() == CoordinateGrid::Kind::quantized)
    throw UsageError(option + out +
                     " is Draco-compressed, and Draco reorders faces; write GLB without --draco" +
                     (options.source_faces ? "" : ", or PLY, OBJ, STL"));
  const std::string format = registry.resolve_for_write(out, options.write.format).name;
  if (options.source_faces && format != "glb" && format != "gltf")
    throw UsageError(
        "--source-faces: " + out + " is " + format +
        ", which has no per-vertex attribute to hold it; write .glb or .gltf (or use --provenance)");
}

// Refuses, before any work, an output format that cannot store the model
// within epsilon where it lies (require_grid_holds).
void check_output_precision(const io::Registry& registry, const std::string& out, const TriangleSoup& input,
                            const ToolOptions& options) {
  const Eigen::AlignedBox3d box = bounding_box(input);
  const double epsilon = epsilon_for(input, options.tetrahedralize);
  io::WriteOptions write = options.write;
  require_grid_holds(output_grid(registry, out, epsilon, options, write)(box.min(), box.max()), out, box,
                     epsilon);
}

// What the holes-only path kept, for its closing line.
std::string kept_faces_phrase(const HolesOnlyRepair& holes) {
  std::string phrase;
  if (holes.repeated_faces != 0) phrase += std::to_string(holes.repeated_faces) + " repeated faces dropped, ";
  if (holes.zero_area_dropped != 0)
    phrase += std::to_string(holes.zero_area_dropped) + " zero-area faces taken out, " +
              std::to_string(holes.split_faces) + " faces split where one lay on their edge, ";
  if (holes.flipped_faces != 0) phrase += std::to_string(holes.flipped_faces) + " faces turned, ";
  if (holes.defects_cut())
    phrase += std::to_string(holes.cut.cut_faces) + " faces cut out around " +
              std::to_string(holes.cut.defect_faces) + " defect faces, ";
  return phrase + (phrase.empty() ? "every input face kept" : "every other input face kept");
}

// What run() read and decided before rebuilding the surface.
struct RebuildInput {
  const TriangleSoup& input;
  double seconds_read = 0.0;
  std::string declined;             ///< why the holes-only path declined
  double seconds_holes_only = 0.0;  ///< what finding that out cost
  KeepInputOutcome keep_input;
  DefectCut cut;                  ///< the defects the holes-only path found and could not cut out
  std::optional<OuterHull> hull;  ///< rebuilt instead of the input where that cost too much
};

// The holes-only path: its holes filled (its local defects cut out), the
// input written back with the patches, checked as written. False (nothing
// written, why in in.declined) when it declines.
bool try_holes_only(const ToolOptions& options, const io::Registry& registry,
                    const std::vector<std::string>& files, RebuildInput& in, std::ostream& out) {
  const TriangleSoup& input = in.input;
  if (options.rebuild == RebuildMode::remesh) {
    in.declined = "--remesh";
    return false;
  }
  auto start = std::chrono::steady_clock::now();
  io::WriteOptions write_options = options.write;
  const Eigen::AlignedBox3d box = bounding_box(input);
  const double epsilon = epsilon_for(input, options.tetrahedralize);
  const CoordinateGrid grid =
      output_grid(registry, files[1], epsilon, options, write_options)(box.min(), box.max());
  const HolesOnlyRepair holes = repair_holes_only(input, grid, epsilon);
  const double seconds_fill = seconds_since(start);
  in.declined = holes.declined;
  in.cut = holes.cut;
  in.seconds_holes_only = seconds_fill;
  if (!holes.fill) return false;
  start = std::chrono::steady_clock::now();
  OutputProvenance provenance;
  const SurfaceWrite written =  // repair_holes_only checked it watertight
      write_watertight_surface(
          registry, holes.fill->surface, files[1], write_options, !options.draco_position_bits,
          [&](const TriangleSoup& rounded, const CoordinateGrid& rounded_grid) {
            return dressed(rounded, rounded_grid, input, epsilon, options.source_faces, provenance);
          });
  const double seconds_write = seconds_since(start) - written.written.seconds;
  write_provenance(options, provenance);
  if (!options.stats_path.empty())
    cli::write_stats_file(options.stats_path,
                          make_holes_only_stats({input, holes, written, provenance.summary, epsilon,
                                                 in.seconds_read, seconds_fill, seconds_write})
                              .dump(2));
  if (!options.quiet)
    out << files[0] << ": " << input.triangles.size() << " faces -> " << holes.fill->surface.triangles.size()
        << " faces, watertight (" << holes.fill->holes.size() << " holes filled, " << kept_faces_phrase(holes)
        << ")\n";
  return true;
}

// The outer hull is rebuilt within the input's epsilon, and it is clean: no budget.
tetmesh::TetrahedralizeOptions hull_or_input_options(const ToolOptions& options, const RebuildInput& in) {
  return in.hull ? hull_rebuild_options(options.tetrahedralize, in.input) : options.tetrahedralize;
}

std::string hull_phrase(const RebuildInput& in) {
  if (!in.hull) return "";
  return "outer hull on voxels of " + std::to_string(in.hull->voxel_size) + ", ";
}

// Tets, surface repair, the written file and its figures, in `mode` (which
// becomes remesh where keeping the input costs too much, the reason kept in
// in.keep_input.abandoned).
void rebuild_and_write(const ToolOptions& options, const io::Registry& registry,
                       const std::vector<std::string>& files, RebuildInput& in, RebuildMode& mode,
                       std::ostream& out, std::ostream& err) {
  const TriangleSoup& input = in.input;
  const TriangleSoup& surface = in.hull ? in.hull->surface : input;
  RepairTetsOptions tets_options;
  tets_options.keep_or_nothing = options.rebuild == RebuildMode::keep_input;
  if (!in.hull)
    tets_options.rebuild_budget = rebuild_budget_for(input.triangles.size(), options.rebuild_budget);
  tets_options.logger = make_logger(options, err);
  if (!options.quiet)
    tets_options.on_give_way = [&err](const std::string& why, const std::string& next) {
      err << "meshrepair: keeping the input triangles would cost too much (" << why << "); " << next << "\n";
    };
  const RepairTets tets =
      tetrahedralize_for_repair(surface, hull_or_input_options(options, in), mode, tets_options);
  const tetmesh::PipelineResult& pipeline = tets.pipeline;
  if (mode != tets.mode) in.keep_input.abandoned = tets.gave_way.back();
  mode = tets.mode;
  in.keep_input.band_rings = tets.band_rings;
  in.keep_input.gave_way = tets.gave_way;
  in.keep_input.seconds_gave_way = tets.seconds_gave_way;
  repair::RepairOptions repair_options =
      surface_repair_options(pipeline, options.tetrahedralize.threads, options.cleanup, mode);
  io::WriteOptions write_options = options.write;
  repair_options.output_grid =
      output_grid(registry, files[1], pipeline.parameters.epsilon, options, write_options);
  repair_options.finer_output_grid = finer_output_grid(registry, files[1], options, write_options);
  const repair::RepairResult repaired =
      repair::repair_surface_from_tets(pipeline.mesh, inside_labels(pipeline), surface, repair_options);
  write_on_grid(write_options, repaired.grid);
  if (options.verbose && !options.quiet) {
    for (const repair::StageTime& stage : repaired.stages)
      err << "meshrepair: end " << stage.name << " (" << stage.seconds << " s)\n";
  }

  const auto start = std::chrono::steady_clock::now();
  check::WrittenFileReport written;
  OutputProvenance provenance;
  io::write_surface(registry,
                    dressed(repaired.surface, repaired.grid, input, pipeline.parameters.epsilon,
                            options.source_faces, provenance),
                    files[1], write_options, check::watertight_file_check(registry, files[1], &written));
  const double seconds_write = seconds_since(start) - written.seconds;
  write_provenance(options, provenance);
  if (!options.stats_path.empty())
    cli::write_stats_file(
        options.stats_path,
        make_repair_stats({input, pipeline, repaired, written, provenance.summary, in.seconds_read,
                           in.seconds_holes_only, seconds_write, in.declined, in.keep_input, in.cut,
                           in.hull ? &*in.hull : nullptr})
            .dump(2));
  if (!options.quiet)
    out << files[0] << ": " << input.triangles.size() << " faces -> " << repaired.surface.triangles.size()
        << " faces, watertight (" << hull_phrase(in)
        << repaired.manifold.nonmanifold_edges_found + repaired.manifold.nonmanifold_vertices_found
        << " non-manifold spots resolved, " << kept_phrase(provenance.summary) << ", epsilon "
        << pipeline.parameters.epsilon << ")\n";
}

// Where rebuilding every face would cost too much (insertion passed its
// budget), the outer hull of the input is rebuilt instead: always closed,
// a few epsilons away.
void rebuild_or_take_hull(const ToolOptions& options, const io::Registry& registry,
                          const std::vector<std::string>& files, RebuildInput& in, RebuildMode& mode,
                          std::ostream& out, std::ostream& err) {
  const auto start = std::chrono::steady_clock::now();
  try {
    rebuild_and_write(options, registry, files, in, mode, out, err);
    return;
  } catch (const tetmesh::RebuildTooCostly& e) {
    if (!options.quiet)
      err << "meshrepair: rebuilding the input would cost too much (" << e.what()
          << "); rebuilding its outer hull on a voxel grid instead\n";
    const double seconds_tried = seconds_since(start);
    in.hull = outer_hull_of(in.input, epsilon_for(in.input, options.tetrahedralize));
    in.hull->reason = e.what();
    in.hull->seconds_rebuild_tried = seconds_tried;
  }
  mode = RebuildMode::remesh;
  rebuild_and_write(options, registry, files, in, mode, out, err);
}

void run(const ToolOptions& options, const std::vector<std::string>& files, std::ostream& out,
         std::ostream& err) {
  const io::Registry registry = io::make_default_registry();
  check_provenance_request(options, registry, files[1]);
  const auto start = std::chrono::steady_clock::now();
  check_file_fits(files[0], options.max_memory);
  const TriangleSoup input = io::read_surface(registry, files[0]);
  RebuildInput rebuild{input, seconds_since(start), {}, 0.0, {}, {}, {}};
  check_faces_fit(files[0], input.num_triangles(), kPipelineBytesPerFace, options.max_memory);
  check_has_area(files[0], input);
  check_output_precision(registry, files[1], input, options);
  if (try_holes_only(options, registry, files, rebuild, out)) return;
  if (options.verbose && !options.quiet)
    err << "meshrepair: rebuilding the surface (" << rebuild.declined << ")\n";
  RebuildMode mode = rebuild_mode(input.triangles.size(), options.rebuild);
  const auto start_rebuild = std::chrono::steady_clock::now();
  try {
    rebuild_or_take_hull(options, registry, files, rebuild, mode, out, err);
  } catch (const RunError& e) {
    // Faces kept as they are give the clean-up and the rounding to the
    // output's grid less room; the full rebuild always has it. --keep-input
    // asked for the input kept or nothing.
    if (mode != RebuildMode::keep_input || options.rebuild) throw;
    if (!options.quiet)
      err << "meshrepair: keeping the input failed (" << e.what() << "); rebuilding the surface instead\n";
    mode = RebuildMode::remesh;
    rebuild.keep_input.abandoned = e.what();
    rebuild.keep_input.seconds_abandoned = seconds_since(start_rebuild);
    rebuild_or_take_hull(options, registry, files, rebuild, mode, out, err);
  }
}

}  // namespace

int meshrepair(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err,
                       [&](const std::vector<std::string>& files) { run(options, files, out, err); });
}

}  // namespace mr::tools
