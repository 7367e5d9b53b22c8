#include "extract_boundary.h"
#include "surface_output.h"

#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/tet_boundary.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <climits>
#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  repair::BoundaryRequest request;
  io::WriteOptions write;
  std::string stats_path;
  int threads = 0;
  bool label_given = false;
  bool interfaces = false;
  bool quiet = false;
  bool verbose = false;
};

struct BoundaryRun {
  std::size_t tets = 0;
  std::size_t faces = 0;
  double seconds_read = 0.0;
  double seconds_boundary = 0.0;
  double seconds_write = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

cli::ToolSpec make_spec(ToolOptions& o) {
  cli::ToolSpec spec;
  spec.name = "extract-boundary";
  spec.summary = "Write the boundary surface of a tet mesh, oriented outward.";
  spec.positionals = {"IN", "OUT"};
  spec.description =
      "IN is a volume mesh (MSH, Medit .mesh); OUT any surface format. By default the boundary\n"
      "of all tets; with --label N the boundary of the tets labelled N; with --interfaces the\n"
      "outer boundary and every face between tets of different labels, each once, its region\n"
      "the smaller of the two labels. Faces point out of their tets (out of the tet with the\n"
      "smaller label for interfaces); inverted tets in the file are flipped first.";
  spec.options = {
      {"--label", "", "N", "boundary of the tets with label N only",
       [&](const std::string& v) {
         o.request.label = cli::parse_int("--label", v, INT_MIN, INT_MAX);
         o.label_given = true;
       }},
      {"--interfaces", "", "", "all interfaces between labels, plus the outer boundary",
       [&](const std::string&) { o.interfaces = true; }},
      cli::ascii_option(o.write.binary),
      cli::stats_option(o.stats_path, "write tets, boundary faces and seconds per step as JSON"),
      cli::threads_option(o.threads),
      cli::quiet_option(o.quiet),
      cli::verbose_option(o.verbose, "also print the seconds of reading, extracting and writing"),
  };
  return spec;
}

BoundaryRun run(const ToolOptions& o, const std::vector<std::string>& files) {
  const io::Registry registry = io::make_default_registry();
  BoundaryRun r;
  auto start = std::chrono::steady_clock::now();
  const TetMesh mesh = io::read_volume(registry, files[0]);
  r.seconds_read = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const TriangleSoup boundary = repair::tet_mesh_boundary(mesh, o.request);
  r.seconds_boundary = seconds_since(start);
  start = std::chrono::steady_clock::now();
  if (o.interfaces)  // interfaces are not one closed surface
    io::write_surface(registry, boundary, files[1], o.write);
  else
    write_surface_keeping_watertight(registry, boundary, files[1], o.write);
  r.seconds_write = seconds_since(start);
  r.tets = mesh.tets.size();
  r.faces = boundary.triangles.size();
  return r;
}

nlohmann::json make_stats(const BoundaryRun& r) {
  return {
      {"tets", r.tets},
      {"boundary_faces", r.faces},
      {"seconds", {{"read", r.seconds_read}, {"boundary", r.seconds_boundary}, {"write", r.seconds_write}}}};
}

}  // namespace

int extract_boundary(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    if (options.label_given && options.interfaces)
      throw UsageError("--label and --interfaces exclude each other");
    options.request.mode = options.interfaces    ? repair::BoundaryMode::interfaces
                           : options.label_given ? repair::BoundaryMode::label
                                                 : repair::BoundaryMode::all;
    BoundaryRun r;
    cli::run_with_threads(options.threads, [&] { r = run(options, files); });
    if (!options.stats_path.empty()) cli::write_stats_file(options.stats_path, make_stats(r).dump(2));
    if (options.quiet) return;
    out << files[0] << ": " << r.tets << " tets -> " << r.faces << " boundary faces\n";
    if (options.verbose)
      err << "extract-boundary: read " << r.seconds_read << " s, boundary " << r.seconds_boundary
          << " s, write " << r.seconds_write << " s\n";
  });
}

}  // namespace mr::tools
