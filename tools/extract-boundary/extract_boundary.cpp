#include "extract_boundary.h"

#include <mr/check/surface_check.h>
#include <mr/check/written_file.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/round_to_grid.h>
#include <mr/repair/tet_boundary.h>

#include <climits>
#include <ostream>

namespace mr::tools {
namespace {

struct ToolOptions {
  repair::BoundaryRequest request;
  bool label_given = false;
  bool interfaces = false;
  bool quiet = false;
};

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
      {"--quiet", "-q", "", "print nothing on success", [&](const std::string&) { o.quiet = true; }},
  };
  return spec;
}

// A boundary that is watertight in doubles stays so in the written file:
// its vertices go onto the grid the format stores (repair::round_to_grid),
// and the file is read back and checked before it is renamed into place.
// Other boundaries (open, pinched, interfaces) are written as they are.
void write_boundary(const io::Registry& registry, TriangleSoup boundary, const std::string& path, bool interfaces) {
  if (interfaces || boundary.triangles.empty() || !check::check_surface(boundary).watertight()) {
    io::write_surface(registry, boundary, path);
    return;
  }
  Vec3d lo = boundary.positions.front(), hi = lo;
  for (const Vec3d& p : boundary.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  io::WriteOptions options;
  const CoordinateGrid grid = io::surface_position_grid(registry, path, options, lo, hi);
  if (grid.kind() == CoordinateGrid::Kind::quantized) options.draco.position_grid = grid.quantization();
  repair::round_to_grid(boundary, grid);
  io::write_surface(registry, boundary, path, options, check::watertight_file_check(registry, path));
}

}  // namespace

int extract_boundary(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  ToolOptions options;
  const cli::ToolSpec spec = make_spec(options);
  return cli::run_tool(spec, args, out, err, [&](const std::vector<std::string>& files) {
    if (options.label_given && options.interfaces) throw UsageError("--label and --interfaces exclude each other");
    options.request.mode = options.interfaces    ? repair::BoundaryMode::interfaces
                           : options.label_given ? repair::BoundaryMode::label
                                                 : repair::BoundaryMode::all;
    const io::Registry registry = io::make_default_registry();
    const TetMesh mesh = io::read_volume(registry, files[0]);
    const TriangleSoup boundary = repair::tet_mesh_boundary(mesh, options.request);
    write_boundary(registry, boundary, files[1], options.interfaces);
    if (!options.quiet)
      out << files[0] << ": " << mesh.tets.size() << " tets -> " << boundary.triangles.size()
          << " boundary faces\n";
  });
}

}  // namespace mr::tools
