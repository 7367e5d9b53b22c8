#include "hole_fill_tool.h"
#include "surface_output.h"

#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/hole_fill/hole_fill.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <climits>
#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  hole_fill::HoleFillOptions fill;
  io::WriteOptions write;
  std::string stats_path;
  int threads = 0;
  bool quiet = false;
  bool verbose = false;
};

struct FillRun {
  std::size_t input_faces = 0;
  hole_fill::HoleFillResult result;
  SurfaceWrite written;
  double seconds_read = 0.0, seconds_fill = 0.0, seconds_write = 0.0;
};

cli::ToolSpec make_spec(ToolOptions& o) {
  cli::ToolSpec spec;
  spec.name = "hole-fill";
  spec.summary = "Close the holes of a surface and change nothing else.";
  spec.positionals = {"IN", "OUT"};
  spec.description =
      "Every loop of border edges (after welding identical positions) is closed by a patch: the\n"
      "triangulation of least worst dihedral angle, then least area (Liepa 2003), refined to the\n"
      "density around it and faired so that it meets the surface smoothly. A patch must meet the\n"
      "surface only along its loop, decided exactly; one that does not is retried with other\n"
      "triangulations, with and without new vertices. Input faces and vertices are kept as they\n"
      "are (to the precision OUT stores). Exit 1 when a selected hole could not be filled or border\n"
      "edges form no loop; -v and --stats say why for each hole.";
  spec.options = {
      {"--max-boundary", "", "N", "leave open holes of more than N border edges",
       [&](const std::string& v) {
         o.fill.max_boundary = std::size_t(cli::parse_int("--max-boundary", v, 3, INT_MAX));
       }},
      {"--max-diameter", "", "D",
       "leave open holes whose border's bounding box diagonal exceeds D (model units)",
       [&](const std::string& v) {
         o.fill.max_diameter = cli::parse_double("--max-diameter", v);
         if (!(o.fill.max_diameter > 0.0)) throw UsageError("--max-diameter must be positive, got " + v);
       }},
      {"--fair", "", "0|1|2", "0: no fairing; 1: tangent-continuous (default); 2: curvature-continuous",
       [&](const std::string& v) { o.fill.fairing = hole_fill::Fairing(cli::parse_int("--fair", v, 0, 2)); }},
      {"--density", "", "keep|coarse",
       "keep: new vertices at the density around the hole (default); coarse: the loop's triangulation only",
       [&](const std::string& v) {
         if (v != "keep" && v != "coarse") throw UsageError("--density must be keep or coarse, got " + v);
         o.fill.density = v == "keep" ? hole_fill::Density::keep : hole_fill::Density::coarse;
       }},
      cli::ascii_option(o.write.binary),
      cli::stats_option(o.stats_path,
                        "write holes found, filled and skipped (with why), patch faces and seconds per "
                        "hole as JSON"),
      cli::threads_option(o.threads),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose, "also print every hole"),
  };
  return spec;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

FillRun run(ToolOptions o, const std::vector<std::string>& files) {
  const io::Registry registry = io::make_default_registry();
  FillRun r;
  auto start = std::chrono::steady_clock::now();
  const TriangleSoup input = io::read_surface(registry, files[0]);
  r.input_faces = input.triangles.size();
  r.seconds_read = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const Eigen::AlignedBox3d box = bounding_box(input);
  // Draco: a grid step of at most 1/64 of meshrepair's default epsilon (1e-3 of the diagonal).
  const double epsilon = 1e-3 * box.diagonal().norm();
  o.write.draco.position_bits = draco_position_bits_for(box.sizes().maxCoeff(), epsilon);
  o.fill.grid = io::surface_position_grid(registry, files[1], o.write, box.min(), box.max());
  require_grid_holds(o.fill.grid, files[1], box, epsilon);
  r.result = hole_fill::fill_holes(input, o.fill);
  r.seconds_fill = seconds_since(start);
  start = std::chrono::steady_clock::now();
  r.written = write_surface_keeping_watertight(registry, r.result.surface, files[1], o.write);
  r.seconds_write = seconds_since(start);
  return r;
}

std::size_t count(const FillRun& r, hole_fill::HoleOutcome outcome) {
  std::size_t n = 0;
  for (const hole_fill::HoleReport& h : r.result.holes) n += h.outcome == outcome;
  return n;
}

nlohmann::json make_stats(const FillRun& r) {
  using hole_fill::HoleOutcome;
  nlohmann::json holes = nlohmann::json::array();
  std::size_t patch_faces = 0, patch_vertices = 0;
  for (const hole_fill::HoleReport& h : r.result.holes) {
    holes.push_back({{"border_edges", h.border_edges},
                     {"diameter", h.diameter},
                     {"outcome", hole_fill::to_string(h.outcome)},
                     {"method", h.method},
                     {"why", h.why},
                     {"attempts", h.attempts},
                     {"patch_faces", h.patch_faces},
                     {"patch_vertices", h.patch_vertices},
                     {"seconds", h.seconds}});
    patch_faces += h.patch_faces;
    patch_vertices += h.patch_vertices;
  }
  return {{"input_faces", r.input_faces},
          {"output_faces", r.result.surface.triangles.size()},
          {"holes_found", r.result.holes.size()},
          {"holes_filled", count(r, HoleOutcome::filled)},
          {"holes_skipped",
           {{"too_long", count(r, HoleOutcome::too_long)}, {"too_wide", count(r, HoleOutcome::too_wide)}}},
          {"holes_failed", count(r, HoleOutcome::failed)},
          {"open_border_edges", r.result.open_border_edges},
          {"patch_faces", patch_faces},
          {"patch_vertices", patch_vertices},
          {"watertight", r.written.watertight},
          {"check_written", r.written.written.seconds},
          {"rounded_vertices", r.written.rounding.moved},
          {"holes", holes},
          {"seconds", {{"read", r.seconds_read}, {"fill", r.seconds_fill}, {"write", r.seconds_write}}}};
}

void print_holes(const FillRun& r, std::ostream& err) {
  for (std::size_t i = 0; i < r.result.holes.size(); ++i) {
    const hole_fill::HoleReport& h = r.result.holes[i];
    err << "hole-fill: hole " << i << ": " << h.border_edges << " border edges, "
        << hole_fill::to_string(h.outcome);
    if (h.outcome == hole_fill::HoleOutcome::filled)
      err << " by " << h.method << " (" << h.patch_faces << " faces, " << h.seconds << " s)";
    else if (h.outcome == hole_fill::HoleOutcome::failed)
      err << " (" << h.attempts << " patches refused; last: " << h.why << ")";
    err << "\n";
  }
}

}  // namespace

int hole_fill(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    FillRun r;
    cli::run_with_threads(options.threads, [&] { r = run(options, files); });
    if (!options.stats_path.empty()) cli::write_stats_file(options.stats_path, make_stats(r).dump(2));
    if (options.verbose && !options.quiet) print_holes(r, err);
    const std::size_t failed = count(r, hole_fill::HoleOutcome::failed);
    if (!options.quiet)
      out << files[0] << ": " << r.result.holes.size() << " holes, " << r.result.filled() << " filled ("
          << r.input_faces << " -> " << r.result.surface.triangles.size() << " faces"
          << (r.written.watertight ? ", watertight" : "") << ")\n";
    std::string unfilled;
    if (failed > 0)
      unfilled = std::to_string(failed) + " holes could not be filled without the patch meeting the surface";
    if (r.result.open_border_edges > 0)
      unfilled +=
          (unfilled.empty() ? "" : "; ") + std::to_string(r.result.open_border_edges) +
          " border edges are on no loop (they end where an edge of three or more faces meets the border)";
    if (!unfilled.empty())
      throw RunError(files[0] + ": " + unfilled + " (the rest is written to " + files[1] + ")");
  });
}

}  // namespace mr::tools
