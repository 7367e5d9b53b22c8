#include "mesh_check.h"

#include <mr/check/distance.h>
#include <mr/check/tet_check.h>
#include <mr/cli/run_tool.h>
#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/io/text_encoding.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <fstream>
#include <ostream>

namespace mr::tools {
namespace {

enum class Expectation { automatic, watertight, valid_tets, none };

struct CheckOptions {
  std::string reference;     // input the mesh was made from, for distances
  double epsilon = 1e-3;     // relative to the reference's bbox diagonal
  double epsilon_abs = 0.0;  // absolute; overrides epsilon when > 0
  bool self_intersections = true;
  Expectation expect = Expectation::automatic;
  std::string json_path;
  int threads = 0;
  bool quiet = false;
  bool verbose = false;
};

nlohmann::json to_json(const check::SurfaceReport& r) {
  return {{"vertices", r.vertices},
          {"faces", r.faces},
          {"boundary_edges", r.boundary_edges},
          {"nonmanifold_edges", r.nonmanifold_edges},
          {"nonmanifold_vertices", r.nonmanifold_vertices},
          {"inconsistent_edges", r.inconsistent_edges},
          {"degenerate_faces", r.degenerate_faces},
          {"duplicate_faces", r.duplicate_faces},
          {"components", r.components},
          {"self_intersecting_pairs", r.self_intersecting_pairs},
          {"volume", r.volume},
          {"closed", r.closed()},
          {"manifold", r.manifold()},
          {"watertight", r.watertight()}};
}

nlohmann::json to_json(const check::TetReport& r) {
  auto finite = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json("inf"); };
  return {{"vertices", r.vertices},
          {"tets", r.tets},
          {"inverted_tets", r.inverted_tets},
          {"degenerate_tets", r.degenerate_tets},
          {"volume", r.volume},
          {"min_dihedral_deg", r.min_dihedral_deg},
          {"avg_min_dihedral_deg", r.avg_min_dihedral_deg},
          {"max_amips", finite(r.max_amips)},
          {"avg_amips", finite(r.avg_amips)},
          {"valid", r.valid()},
          {"boundary", to_json(r.boundary)}};
}

cli::ToolSpec make_spec(CheckOptions& o) {
  cli::ToolSpec spec;
  spec.name = "mesh-check";
  spec.summary = "Verify a surface or tet mesh and print a JSON report.";
  spec.positionals = {"FILE"};
  spec.description =
      "Surfaces: closed, manifold, consistently oriented, outward, no degenerate face, no\n"
      "self-intersection (exact). Tet meshes: every tet positively oriented (exact, on the\n"
      "stored doubles), quality, and the same surface checks on the boundary.\n"
      "Exit 0 if the mesh meets the expectation, 1 if not, 2 if it cannot be read.";
  spec.options = {
      {"--reference", "-r", "INPUT", "also measure distances to/from this surface (sampled)",
       [&](const std::string& v) { o.reference = v; }},
      {"--epsilon", "-e", "EPS", "distance bound relative to the reference's bbox diagonal (default 1e-3)",
       [&](const std::string& v) { o.epsilon = cli::parse_double("--epsilon", v); }},
      {"--epsilon-abs", "", "EPS", "absolute distance bound (overrides --epsilon)",
       [&](const std::string& v) { o.epsilon_abs = cli::parse_double("--epsilon-abs", v); }},
      {"--no-self-intersections", "", "", "skip the exact self-intersection test",
       [&](const std::string&) { o.self_intersections = false; }},
      {"--expect", "", "WHAT", "watertight, valid-tets or none (default: by file kind)",
       [&](const std::string& v) {
         if (v == "watertight")
           o.expect = Expectation::watertight;
         else if (v == "valid-tets")
           o.expect = Expectation::valid_tets;
         else if (v == "none")
           o.expect = Expectation::none;
         else
           throw UsageError("--expect must be watertight, valid-tets or none");
       }},
      {"--json", "", "FILE", "also write the report to FILE", [&](const std::string& v) { o.json_path = v; }},
      cli::stats_option(o.json_path, "the same as --json (the family's name for a tool's figures)"),
      cli::threads_option(o.threads),
      {"--quiet", "-q", "", "print no report; the exit code says whether the mesh meets the expectation",
       [&](const std::string&) { o.quiet = true; }},
      cli::verbose_option(o.verbose, "also print the seconds of reading and checking"),
  };
  return spec;
}

// Adds sampled distances both ways; returns whether output-to-reference stays within epsilon.
bool add_distances(const io::Registry& registry, const TriangleSoup& surface, const CheckOptions& o,
                   nlohmann::json& report) {
  const TriangleSoup reference = io::read_surface(registry, o.reference);
  const double diagonal = bounding_box_diagonal(reference);
  const check::DistanceReport to_ref = check::one_sided_distance(surface, reference);
  const check::DistanceReport from_ref = check::one_sided_distance(reference, surface);
  const double bound = o.epsilon_abs > 0.0 ? o.epsilon_abs : o.epsilon * diagonal;
  report["distance"] = {
      {"reference", io::as_utf8(o.reference)},
      {"bbox_diagonal", diagonal},
      {"epsilon_abs", bound},
      {"to_reference_max", to_ref.max},
      {"to_reference_mean", to_ref.mean},
      {"to_reference_farthest", {to_ref.farthest.x(), to_ref.farthest.y(), to_ref.farthest.z()}},
      {"from_reference_max", from_ref.max},
      {"from_reference_farthest", {from_ref.farthest.x(), from_ref.farthest.y(), from_ref.farthest.z()}},
      {"from_reference_mean", from_ref.mean},
      {"to_reference_max_rel", diagonal > 0 ? to_ref.max / diagonal : 0.0},
      {"from_reference_max_rel", diagonal > 0 ? from_ref.max / diagonal : 0.0},
      {"samples", to_ref.samples + from_ref.samples}};
  return to_ref.max <= bound;
}

bool check_file(const std::string& path, const CheckOptions& o, nlohmann::json& report) {
  const io::Registry registry = io::make_default_registry();
  const bool volume = io::is_volume_format(registry, path);
  check::SurfaceCheckOptions surface_options;
  surface_options.self_intersections = o.self_intersections;
  Expectation expect = o.expect;
  if (expect == Expectation::automatic) expect = volume ? Expectation::valid_tets : Expectation::watertight;

  bool ok = true;
  TriangleSoup surface;
  report["file"] = io::as_utf8(path);  // JSON strings must be UTF-8; file names need not be
  if (volume) {
    const TetMesh mesh = io::read_volume(registry, path);
    const check::TetReport tets = check::check_tets(mesh, surface_options);
    report["kind"] = "volume";
    report["tets"] = to_json(tets);
    if (expect == Expectation::valid_tets) ok = tets.valid() && tets.boundary.closed();
    if (expect == Expectation::watertight) ok = tets.valid() && tets.boundary.watertight();
    surface = extract_boundary(mesh);
  } else {
    surface = io::read_surface(registry, path);
    const check::SurfaceReport r = check::check_surface(surface, surface_options);
    report["kind"] = "surface";
    report["surface"] = to_json(r);
    if (expect == Expectation::valid_tets)
      throw UsageError(path + " is a surface; --expect valid-tets needs a tet mesh");
    if (expect == Expectation::watertight) ok = r.watertight();
  }
  if (!o.reference.empty()) ok = add_distances(registry, surface, o, report) && ok;
  report["ok"] = ok;
  return ok;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int mesh_check(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CheckOptions options;
  const cli::ToolSpec spec = make_spec(options);
  bool ok = true;
  const int code = cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    if (options.epsilon_abs < 0.0) throw UsageError("--epsilon-abs must be >= 0");
    nlohmann::json report;
    const auto start = std::chrono::steady_clock::now();
    cli::run_with_threads(options.threads, [&] { ok = check_file(files[0], options, report); });
    if (!options.quiet) out << report.dump(2) << "\n";
    if (!options.json_path.empty()) cli::write_stats_file(options.json_path, report.dump(2));
    if (options.verbose && !options.quiet)
      err << "mesh-check: " << files[0] << " read and checked in " << seconds_since(start) << " s\n";
  });
  return code == cli::exit_ok && !ok ? int(cli::exit_failure) : code;
}

}  // namespace mr::tools
