#include "tetrahedralize.h"
#include "memory_budget.h"
#include "surface_input.h"

#include <mr/check/distance.h>
#include <mr/check/tet_check.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/tetmesh/sizing_field.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <nlohmann/json.hpp>

#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  tetmesh::PipelineOptions pipeline;
  io::WriteOptions write;
  std::string stats_path;
  std::string surface_path;
  std::string sizing_path;
  std::size_t max_memory = cli::default_max_memory();
  bool quiet = false;
  bool verbose = false;
};

cli::ToolSpec make_spec(ToolOptions& o) {
  using cli::parse_double;
  using cli::parse_int;
  cli::ToolSpec spec;
  spec.name = "tetrahedralize";
  spec.summary = "Turn any triangle soup into a valid tetrahedral mesh of the solid it describes.";
  spec.positionals = {"IN", "OUT"};
  spec.description =
      "Simplify the input inside its epsilon-envelope, build a background Delaunay mesh, insert\n"
      "every input triangle exactly (it becomes a union of mesh faces; coplanar neighbours are\n"
      "inserted together as one convex polygon), round cut points to doubles where no tet\n"
      "inverts, and keep the tets whose centroid has winding number |w| > 1/2.\n"
      "OUT: .msh (MSH 4.1 by default), .mesh (Medit) or .vtu. Every written tet is positively\n"
      "oriented on the written coordinates (exact check). Output is the same for any -j.";
  auto& t = o.pipeline.tetrahedralize;
  spec.options = {
      {"--epsilon", "-e", "EPS", "envelope radius relative to the bbox diagonal (default 1e-3)",
       [&](const std::string& v) { t.epsilon_rel = parse_double("--epsilon", v); }},
      {"--epsilon-abs", "", "EPS", "absolute envelope radius (overrides --epsilon)",
       [&](const std::string& v) { t.epsilon_abs = parse_double("--epsilon-abs", v); }},
      {"--edge-length", "-l", "LEN", "target edge length relative to the bbox diagonal (default 0.05)",
       [&](const std::string& v) { t.edge_length_rel = parse_double("--edge-length", v); }},
      {"--edge-length-abs", "", "LEN", "absolute target edge length (overrides --edge-length)",
       [&](const std::string& v) { t.edge_length_abs = parse_double("--edge-length-abs", v); }},
      {"--lattice", "", "H",
       "voxel-stuffing lattice spacing relative to the bbox diagonal, at least the target edge length "
       "(default 0.05; 0: none)",
       [&](const std::string& v) { t.lattice_spacing_rel = parse_double("--lattice", v); }},
      {"--lattice-clearance", "", "D",
       "drop lattice points closer than D (relative to the bbox diagonal, > epsilon) to the input (default "
       "0.025)",
       [&](const std::string& v) { t.lattice_clearance_rel = parse_double("--lattice-clearance", v); }},
      {"--stop-energy", "", "E", "improve until the largest AMIPS energy is below E (default 10)",
       [&](const std::string& v) { t.stop_energy = parse_double("--stop-energy", v); }},
      {"--max-passes", "", "N", "at most N mesh-improvement passes (default 80; 0 skips improvement)",
       [&](const std::string& v) {
         t.max_passes = parse_int("--max-passes", v, 0, 100000);
         o.pipeline.improve = t.max_passes > 0;
       }},
      {"--positive-winding", "", "", "keep only tets with winding number > 1/2 (default |w| > 1/2)",
       [&](const std::string&) { t.winding_rule = tetmesh::WindingRule::positive; }},
      {"--labels", "", "MODE",
       "label the tets by input part: auto (default: by face region when the input has several, e.g. glTF "
       "materials or OBJ groups), regions, components (connected parts of the input), winding (nesting "
       "depth) or none; written as MSH physical groups, Medit references and a VTU cell array",
       [&](const std::string& v) { o.pipeline.labels = tetmesh::tet_labels_named(v); }},
      {"--no-filter", "", "",
       "keep every tet, labelled by region (tets connected without crossing the input)",
       [&](const std::string&) { o.pipeline.filter = false; }},
      {"--snap", "", "F",
       "snap the input to a grid of F times epsilon (a power of two at most) before inserting it, and "
       "move cut points closer than that to a later triangle's plane onto it "
       "(default 1e-3, at most 0.01; 0: insert the coordinates as they are)",
       [&](const std::string& v) { t.snap_fraction = parse_double("--snap", v); }},
      {"--skip-simplify", "", "", "insert the input as it is, without simplifying it first",
       [&](const std::string&) { t.skip_simplify = true; }},
      {"--sizing", "", "FILE",
       "target edge length varying in space, absolute: a tet mesh (.msh) with a value per node ($NodeData "
       "\"values\", fTetWild's --bg-mesh) interpolated linearly, or a float grid (.vdb, the grid \"sizing\" "
       "or the first that is no level set) sampled trilinearly; where it gives no value, -l holds; clamped "
       "to [l/100, 100 l]",
       [&](const std::string& v) { o.sizing_path = v; }},
      {"--surface", "", "FILE", "also write the tracked surface (the input as embedded)",
       [&](const std::string& v) { o.surface_path = v; }},
      {"--msh-version", "", "V", "MSH version to write: 4.1 (default) or 2.2",
       [&](const std::string& v) {
         if (v != "4.1" && v != "2.2") throw UsageError("--msh-version must be 4.1 or 2.2, got " + v);
         o.write.msh_version = v;
       }},
      cli::ascii_option(o.write.binary),
      cli::stats_option(o.stats_path,
                        "write counts, time per stage, peak memory, quality and distance as JSON"),
      cli::threads_option(t.threads),
      cli::max_memory_option(o.max_memory),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose,
                          "also print each stage as it starts and ends, and each improvement pass"),
  };
  return spec;
}

nlohmann::json make_stats(const TriangleSoup& input, const tetmesh::PipelineResult& result,
                          const check::TetReport& quality) {
  const check::DistanceReport distance = check::one_sided_distance(result.tracked_surface, input);
  nlohmann::json stats = nlohmann::json::parse(tetmesh::to_json(result.stats));
  stats["input"] = {{"vertices", input.positions.size()}, {"faces", input.triangles.size()}};
  stats["output"] = {{"vertices", result.mesh.positions.size()},
                     {"tets", result.mesh.tets.size()},
                     {"tracked_surface_faces", result.tracked_surface.triangles.size()},
                     {"volume", quality.volume}};
  stats["quality"] = {{"min_dihedral_deg", quality.min_dihedral_deg},
                      {"avg_min_dihedral_deg", quality.avg_min_dihedral_deg},
                      {"max_amips", quality.max_amips},
                      {"avg_amips", quality.avg_amips},
                      {"inverted_tets", quality.inverted_tets},
                      {"degenerate_tets", quality.degenerate_tets}};
  stats["envelope"] = {{"epsilon", result.parameters.epsilon},
                       {"bbox_diagonal", result.parameters.diagonal},
                       {"tracked_surface_to_input_max", distance.max},
                       {"tracked_surface_to_input_mean", distance.mean},
                       {"samples", distance.samples}};
  stats["peak_memory_mb"] = cli::peak_memory_mb();
  return stats;
}

// A sizing field from a tet mesh with node values, or from a format that
// stores a field (a .vdb float grid).
std::shared_ptr<const ScalarField> read_sizing_field(const io::Registry& registry, const std::string& path) {
  const io::Format& format = registry.resolve_for_read(path, "");
  if (format.read_field) return format.read_field(path);
  if (format.read_volume) return tetmesh::sizing_from_tet_mesh(format.read_volume(path, {}), path);
  throw InputError(path, "a sizing field is a tet mesh with node values (.msh) or a float grid (.vdb), not " +
                             format.description);
}

}  // namespace

int tetrahedralize(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    const io::Registry registry = io::make_default_registry();
    if (!io::is_volume_format(registry, files[1])) {
      throw UsageError(files[1] + ": the output must be a volume format (.msh, .mesh or .vtu)");
    }
    check_file_fits(files[0], options.max_memory);
    const TriangleSoup input = io::read_surface(registry, files[0]);
    check_faces_fit(files[0], input.num_triangles(), kPipelineBytesPerFace, options.max_memory);
    check_has_area(files[0], input);
    if (!options.sizing_path.empty()) {
      check_file_fits(options.sizing_path, options.max_memory);
      options.pipeline.sizing = read_sizing_field(registry, options.sizing_path);
    }
    tetmesh::Logger logger;
    if (!options.quiet) {
      logger.on_message = [&](tetmesh::LogLevel level, std::string_view text) {
        if (level != tetmesh::LogLevel::debug || options.verbose) err << text << std::endl;
      };
    }
    const tetmesh::PipelineResult result = tetmesh::tetrahedralize(input, options.pipeline, logger);
    const check::TetReport quality = check::check_tets(result.mesh, {.self_intersections = false});
    if (quality.tets == 0) {
      throw RunError(files[0] +
                     ": no tet lies inside the input (winding number nowhere above 1/2 in magnitude); "
                     "nothing written. --no-filter keeps every tet");
    }
    if (!quality.valid()) {
      throw RunError("the mesh failed its final exact check (" + std::to_string(quality.inverted_tets) +
                     " inverted, " + std::to_string(quality.degenerate_tets) +
                     " flat tets); nothing written");
    }
    io::write_volume(registry, result.mesh, files[1], options.write);
    if (!options.surface_path.empty())
      io::write_surface(registry, result.tracked_surface, options.surface_path, options.write);
    if (!options.stats_path.empty()) {
      cli::write_stats_file(options.stats_path, make_stats(input, result, quality).dump(2));
    }
    if (!options.quiet) {
      out << files[0] << ": " << result.mesh.tets.size() << " tets, " << result.mesh.positions.size()
          << " vertices, min dihedral " << quality.min_dihedral_deg << " deg, max AMIPS " << quality.max_amips
          << ", " << result.stats.total_seconds() << " s\n";
    }
  });
}

}  // namespace mr::tools
