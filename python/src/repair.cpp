// repair(): the pipeline of the meshrepair tool (tools/meshrepair/meshrepair.cpp,
// run()) on arrays instead of files: the holes-only path when holes are the
// input's only defects, else the tetrahedral fast path and the surface repair.

#include "arrays.h"
#include "bindings.h"
#include "options.h"

#include <fast_path.h>
#include <holes_only_repair.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/repair/repair.h>
#include <mr/tetmesh/insertion.h>
#include <mr/tetmesh/tetrahedralize.h>
#include <outer_hull_path.h>

#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace mr::python {
namespace {

struct RepairArgs {
  tetmesh::TetrahedralizeOptions tetrahedralize = tools::repair_defaults();
  bool remesh = false;
  bool cleanup = true;
  /// Tets the rebuild of every face may make before the outer hull is
  /// rebuilt instead (unset: tools::rebuild_tet_budget; 0: never).
  std::optional<std::size_t> max_tets;
  CoordinateGrid grid = CoordinateGrid::doubles();
};

// Fast path of the tetrahedralization, then the boundary of the kept tets
// made manifold, peeled and cleaned up inside the envelope of the input.
TriangleSoup rebuild_in_mode(const TriangleSoup& input, const RepairArgs& args, tools::RebuildMode mode,
                             std::size_t rebuild_budget) {
  tools::RepairTetsOptions tets_options;
  tets_options.rebuild_budget = rebuild_budget;
  const tools::RepairTets tets =
      tools::tetrahedralize_for_repair(input, args.tetrahedralize, mode, tets_options);
  const tetmesh::PipelineResult& pipeline = tets.pipeline;
  repair::RepairOptions repair_options =
      tools::surface_repair_options(pipeline, args.tetrahedralize.threads, args.cleanup, tets.mode);
  repair_options.output_grid = [grid = args.grid](const Vec3d&, const Vec3d&) { return grid; };
  return repair::repair_surface_from_tets(pipeline.mesh, tools::inside_labels(pipeline), input,
                                          repair_options)
      .surface;
}

// As the tool does: where rebuilding every face passes its budget, the
// input's outer hull is rebuilt instead, within the input's epsilon.
TriangleSoup rebuild_or_take_hull(const TriangleSoup& input, const RepairArgs& args,
                                  tools::RebuildMode mode) {
  try {
    return rebuild_in_mode(input, args, mode,
                           tools::rebuild_budget_for(input.triangles.size(), args.max_tets));
  } catch (const tetmesh::RebuildTooCostly&) {
  }
  RepairArgs hull_args = args;
  hull_args.tetrahedralize = tools::hull_rebuild_options(args.tetrahedralize, input);
  const TriangleSoup hull = tools::outer_hull_of(input, hull_args.tetrahedralize.epsilon_abs).surface;
  return rebuild_in_mode(hull, hull_args, tools::RebuildMode::remesh, 0);
}

// As the tool does: a failure of the kept-input run (the rounding to the
// grid finding no place beside kept faces) gives way to the full rebuild,
// which always has that room.
TriangleSoup rebuild_through_tets(const TriangleSoup& input, const RepairArgs& args) {
  const tools::RebuildMode mode = tools::rebuild_mode(
      input.triangles.size(), args.remesh ? std::optional(tools::RebuildMode::remesh) : std::nullopt);
  try {
    return rebuild_or_take_hull(input, args, mode);
  } catch (const RunError&) {
    if (mode != tools::RebuildMode::keep_input) throw;
    return rebuild_or_take_hull(input, args, tools::RebuildMode::remesh);
  }
}

TriangleSoup repair_soup(const TriangleSoup& input, const RepairArgs& args) {
  if (!args.remesh) {
    tools::HolesOnlyRepair holes =
        tools::repair_holes_only(input, args.grid, tools::epsilon_for(input, args.tetrahedralize));
    if (holes.fill) return std::move(holes.fill->surface);
  }
  return rebuild_through_tets(input, args);
}

constexpr const char* kDoc = R"(Turn any triangle surface into a watertight one.

The meshrepair tool on arrays. The output is closed, edge- and vertex-manifold,
oriented outward, free of self-intersections and zero-area faces, and within
epsilon of the input wherever the input had surface (holes and gaps are
filled). A watertight input comes back as it is, and one whose only defects
are holes, repeated faces, flipped faces or zero-area faces keeps every other
face (the flipped ones turned back) and gets faired patches, at any size
(unless remesh=True), as does one whose other defects are few and local
enough to be cut out and filled within epsilon; any other input goes through the tetrahedral fast path, which
keeps the input triangles away from defects on inputs of up to 50,000 faces
and rebuilds larger ones, or every input with remesh=True.

Args:
    vertices: (N, 3) array of real numbers (any float or integer dtype).
    faces: (M, 3) array of integer vertex indices; may be a soup (duplicated,
        unwelded, degenerate faces).
    epsilon: envelope radius relative to the bounding-box diagonal.
    epsilon_abs: absolute envelope radius; overrides epsilon when > 0.
    lattice: voxel-stuffing lattice spacing of the background mesh relative
        to the bounding-box diagonal (0: none).
    snap: snap the input to a grid of snap * epsilon (a power of two at most)
        before inserting it; 0 inserts the coordinates as they are.
    skip_simplify: insert the input as it is, without simplifying it first.
    remesh: rebuild and simplify the whole surface through the tet mesh, even
        when holes are its only defect.
    cleanup: collapse and flip edges of the peeled surface inside the envelope.
    max_tets: tets rebuilding every face may make before the input's outer
        hull on a voxel grid, a few epsilons from it, is rebuilt instead
        (None: 2,000,000 plus 64 per input face; 0: never).
    grid: "float64", or "float32" for positions that stay watertight once
        written as float32 (STL, GLB).
    threads: worker threads; 0 uses all hardware threads.

Returns:
    (vertices, faces): float64 (N, 3) and int64 (M, 3) arrays.

Raises:
    ValueError: bad arrays or options.
    meshrepair.Error: the repair could not complete (the tool's message).
)";

}  // namespace

void bind_repair(py::module_& m) {
  const RepairArgs d;
  m.def(
      "repair",
      [](const ArrayLike& vertices, const ArrayLike& faces, double epsilon, double epsilon_abs,
         double lattice, double snap, bool skip_simplify, bool remesh, bool cleanup,
         std::optional<std::int64_t> max_tets, const std::string& grid, int threads) {
        const TriangleSoup input = soup_from_arrays(vertices, faces);
        RepairArgs args;
        args.tetrahedralize.epsilon_rel = epsilon;
        args.tetrahedralize.epsilon_abs = epsilon_abs;
        args.tetrahedralize.lattice_spacing_rel = lattice;
        args.tetrahedralize.snap_fraction = snap;
        args.tetrahedralize.skip_simplify = skip_simplify;
        args.tetrahedralize.threads = checked_threads(threads);
        args.remesh = remesh;
        args.cleanup = cleanup;
        if (max_tets) {
          if (*max_tets < 0) throw py::value_error("max_tets must be 0 or more");
          args.max_tets = static_cast<std::size_t>(*max_tets);
        }
        args.grid = grid_named(grid);
        const TriangleSoup output = without_gil([&] {
          TriangleSoup surface;
          cli::run_with_threads(args.tetrahedralize.threads, [&] { surface = repair_soup(input, args); });
          return surface;
        });
        return soup_to_arrays(output);
      },
      kDoc, py::arg("vertices"), py::arg("faces"), py::kw_only(),
      py::arg("epsilon") = d.tetrahedralize.epsilon_rel,
      py::arg("epsilon_abs") = d.tetrahedralize.epsilon_abs,
      py::arg("lattice") = d.tetrahedralize.lattice_spacing_rel,
      py::arg("snap") = d.tetrahedralize.snap_fraction,
      py::arg("skip_simplify") = d.tetrahedralize.skip_simplify, py::arg("remesh") = d.remesh,
      py::arg("cleanup") = d.cleanup, py::arg("max_tets") = py::none(), py::arg("grid") = "float64",
      py::arg("threads") = d.tetrahedralize.threads);
}

}  // namespace mr::python
