#include "simplify_in_envelope.h"
#include "surface_output.h"

#include <mr/check/distance.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/simplify/simplify.h>

#include <nlohmann/json.hpp>

#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  simplify::SimplifyOptions simplify;
  io::WriteOptions write;
  std::string stats_path;
  bool quiet = false;
  bool verbose = false;
};

cli::ToolSpec make_spec(ToolOptions& o) {
  using cli::parse_double;
  using cli::parse_int;
  cli::ToolSpec spec;
  spec.name = "simplify-in-envelope";
  spec.summary = "Reduce the face count of a surface while keeping every point within epsilon of the input.";
  spec.positionals = {"IN", "OUT"};
  spec.description =
      "Edge collapses (flat regions and short edges first), then angle-improving edge flips.\n"
      "An operation is accepted only if every changed triangle stays inside the epsilon-envelope\n"
      "of the original input, no face normal turns by more than the allowed deviation, the link\n"
      "condition holds and no new self-intersection appears (exact test). Boundaries stay within\n"
      "epsilon of the input's boundary curve; non-manifold faces pass through unchanged;\n"
      "copies of a face (double-sided surfaces) are simplified as one and all written out.\n"
      "Each patch of faces connected through manifold edges is first oriented coherently, the\n"
      "way most of its area faces; faces that disagreed with it are written reversed.\n"
      "A watertight result is rounded onto the output's grid (float32, Draco's, chosen from\n"
      "epsilon) keeping it watertight, and the written file is checked; a format that cannot\n"
      "store the model within epsilon where it lies is refused before any work.\n"
      "The output is the same for any thread count.";
  auto& s = o.simplify;
  spec.options = {
      {"--epsilon", "-e", "EPS", "envelope radius relative to the bbox diagonal (default 1e-3)",
       [&](const std::string& v) { s.epsilon_rel = parse_double("--epsilon", v); }},
      {"--epsilon-abs", "", "EPS", "absolute envelope radius (overrides --epsilon)",
       [&](const std::string& v) { s.epsilon_abs = parse_double("--epsilon-abs", v); }},
      {"--target-faces", "", "N", "stop at N faces (default: as few as the envelope allows)",
       [&](const std::string& v) {
         s.target_faces = std::size_t(parse_int("--target-faces", v, 0, 2147483647));
       }},
      {"--max-normal-deviation", "", "DEG", "largest normal change of a face per operation (default 60)",
       [&](const std::string& v) { s.max_normal_deviation_deg = parse_double("--max-normal-deviation", v); }},
      {"--flip-passes", "", "N", "sweeps of edge flips after collapsing (default 3, 0 = none)",
       [&](const std::string& v) { s.flip_passes = parse_int("--flip-passes", v, 0, 1000); }},
      cli::ascii_option(o.write.binary),
      cli::stats_option(o.stats_path, "write faces, timings, epsilon and measured distance as JSON"),
      cli::threads_option(s.threads),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose,
                          "also print what was kept aside or locked, and the seconds of each phase"),
  };
  return spec;
}

nlohmann::json make_stats(const ToolOptions& o, const TriangleSoup& input, const simplify::SimplifyResult& r,
                          const SurfaceWrite& w) {
  const check::DistanceReport distance = check::one_sided_distance(r.soup, input);
  const double diagonal = bounding_box_diagonal(input);
  return {{"faces_before", r.faces_before},
          {"faces_after", r.faces_after},
          {"kept_aside_faces", r.kept_aside_faces},
          {"duplicate_faces", r.duplicate_faces},
          {"reoriented_faces", r.reoriented_faces},
          {"locked_vertices", r.locked_vertices},
          {"collapses", r.collapses},
          {"flips", r.flips},
          {"epsilon_rel",
           o.simplify.epsilon_abs > 0.0 && diagonal > 0.0 ? r.epsilon / diagonal : o.simplify.epsilon_rel},
          {"epsilon_abs", r.epsilon},
          {"bbox_diagonal", diagonal},
          {"seconds",
           {{"setup", r.seconds_setup},
            {"collapse", r.seconds_collapse},
            {"flip", r.seconds_flip},
            {"check_written", w.written.seconds}}},
          {"written",
           {{"kept_watertight", w.watertight},
            {"rounded_vertices", w.rounding.moved},
            {"rounding_collapsed", w.rounding.collapsed},
            {"rounding_max_move", w.rounding.max_move}}},
          {"distance_to_input_max", distance.max},
          {"distance_to_input_mean", distance.mean},
          {"distance_samples", distance.samples}};
}

// Refuses, before any work, an output format that cannot store the input
// within epsilon where it lies (require_grid_holds); Draco's bits are
// chosen from epsilon, as meshrepair does.
void check_output_precision(const io::Registry& registry, const std::string& out, const TriangleSoup& input,
                            ToolOptions& options) {
  const Eigen::AlignedBox3d box = bounding_box(input);
  const simplify::SimplifyOptions& s = options.simplify;
  const double epsilon = s.epsilon_abs > 0.0 ? s.epsilon_abs : s.epsilon_rel * box.diagonal().norm();
  if (!(epsilon > 0.0)) return;  // simplify_in_envelope refuses it
  options.write.draco.position_bits = draco_position_bits_for(box.sizes().maxCoeff(), epsilon);
  require_grid_holds(io::surface_position_grid(registry, out, options.write, box.min(), box.max()), out, box,
                     epsilon);
}

void print_details(const simplify::SimplifyResult& r, std::ostream& err) {
  err << "simplify-in-envelope: " << r.reoriented_faces
      << " faces reversed to orient their patch coherently, " << r.kept_aside_faces << " faces kept aside, "
      << r.duplicate_faces << " copies of other faces, " << r.locked_vertices << " vertices locked\n"
      << "simplify-in-envelope: setup " << r.seconds_setup << " s, collapses " << r.seconds_collapse
      << " s, flips " << r.seconds_flip << " s\n";
}

}  // namespace

int simplify_in_envelope(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    const io::Registry registry = io::make_default_registry();
    const TriangleSoup input = io::read_surface(registry, files[0]);
    check_output_precision(registry, files[1], input, options);
    const simplify::SimplifyResult result = simplify::simplify_in_envelope(input, options.simplify);
    // A watertight result is rounded onto the file's grid keeping it so,
    // and checked as written.
    const SurfaceWrite written =
        write_surface_keeping_watertight(registry, result.soup, files[1], options.write);
    if (!options.stats_path.empty()) {
      cli::write_stats_file(options.stats_path, make_stats(options, input, result, written).dump(2));
    }
    if (options.quiet) return;
    out << files[0] << ": " << result.faces_before << " -> " << result.faces_after << " faces ("
        << result.collapses << " collapses, " << result.flips << " flips, epsilon " << result.epsilon
        << ")\n";
    if (options.verbose) print_details(result, err);
  });
}

}  // namespace mr::tools
