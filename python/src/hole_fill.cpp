// fill_holes(): the hole-fill tool on arrays, with its per-hole report.

#include "arrays.h"
#include "bindings.h"
#include "options.h"

#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>
#include <mr/hole_fill/hole_fill.h>

#include <string>

namespace mr::python {
namespace {

hole_fill::Fairing fairing_named(int level) {
  if (level < 0 || level > 2) throw UsageError("fairing must be 0, 1 or 2, got " + std::to_string(level));
  return hole_fill::Fairing(level);
}

hole_fill::Density density_named(const std::string& name) {
  if (name == "keep") return hole_fill::Density::keep;
  if (name == "coarse") return hole_fill::Density::coarse;
  throw UsageError("density must be \"keep\" or \"coarse\", got \"" + name + "\"");
}

py::dict hole_to_dict(const hole_fill::HoleReport& h) {
  py::dict d;
  d["border_edges"] = h.border_edges;
  d["islands"] = h.islands;
  d["diameter"] = h.diameter;
  d["outcome"] = hole_fill::to_string(h.outcome);
  d["method"] = h.method;
  d["why"] = h.why;
  d["attempts"] = h.attempts;
  d["patch_faces"] = h.patch_faces;
  d["patch_vertices"] = h.patch_vertices;
  d["seconds"] = h.seconds;
  return d;
}

py::dict report_to_dict(const hole_fill::HoleFillResult& r) {
  py::list holes;
  for (const hole_fill::HoleReport& h : r.holes) holes.append(hole_to_dict(h));
  py::dict d;
  d["input_faces"] = r.input_faces;
  d["holes_found"] = r.holes.size();
  d["holes_filled"] = r.filled();
  d["open_border_edges"] = r.open_border_edges;
  d["holes"] = holes;
  return d;
}

constexpr const char* kDoc = R"(Close the holes of a surface and change nothing else.

The hole-fill tool on arrays: every boundary loop is closed by a patch
(minimal-dihedral triangulation, refined to the density around it and
faired), accepted only if it meets the rest of the surface exactly in the
loop it closes. Input faces come first, unchanged and in order. A hole that
cannot be filled is left open and reported, not raised.

Args:
    vertices: (N, 3) array of real numbers.
    faces: (M, 3) array of integer vertex indices.
    max_boundary: leave open holes with more border edges than this (0: no limit).
    max_diameter: leave open holes whose border spans more than this (model units).
    fairing: 0 none, 1 tangent-continuous, 2 curvature-continuous.
    density: "keep" adds vertices at the density around the hole; "coarse"
        only triangulates the loop.
    grid: "float64", or "float32" to check new vertices as written in float32.
    threads: worker threads; 0 uses all hardware threads.

Returns:
    (vertices, faces, report): float64 (N, 3) and int64 (M, 3) arrays, and a
    dict with input_faces, holes_found, holes_filled, open_border_edges and
    holes, a list of one dict per hole (border_edges, islands, diameter,
    outcome: "filled", "too_long", "too_wide" or "failed", method, why,
    attempts, patch_faces, patch_vertices, seconds).

Raises:
    ValueError: bad arrays or options.
)";

}  // namespace

void bind_hole_fill(py::module_& m) {
  const hole_fill::HoleFillOptions d;
  m.def(
      "fill_holes",
      [](const ArrayLike& vertices, const ArrayLike& faces, int max_boundary, double max_diameter,
         int fairing, const std::string& density, const std::string& grid, int threads) {
        const TriangleSoup input = soup_from_arrays(vertices, faces);
        hole_fill::HoleFillOptions options;
        options.max_boundary = static_cast<std::size_t>(non_negative("max_boundary", max_boundary));
        if (!(max_diameter > 0.0))
          throw UsageError("max_diameter must be positive, got " + std::to_string(max_diameter));
        options.max_diameter = max_diameter;
        options.fairing = fairing_named(fairing);
        options.density = density_named(density);
        options.grid = grid_named(grid);
        const int workers = checked_threads(threads);
        const hole_fill::HoleFillResult result = without_gil([&] {
          hole_fill::HoleFillResult filled;
          cli::run_with_threads(workers, [&] { filled = hole_fill::fill_holes(input, options); });
          return filled;
        });
        const py::tuple arrays = soup_to_arrays(result.surface);
        return py::make_tuple(arrays[0], arrays[1], report_to_dict(result));
      },
      kDoc, py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("max_boundary") = 0,
      py::arg("max_diameter") = d.max_diameter, py::arg("fairing") = static_cast<int>(d.fairing),
      py::arg("density") = "keep", py::arg("grid") = "float64", py::arg("threads") = 0);
}

}  // namespace mr::python
