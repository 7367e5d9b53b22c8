// tetrahedralize(): the tetrahedralize tool (tools/tetrahedralize) on arrays.

#include "arrays.h"
#include "bindings.h"
#include "options.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/sizing_field.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <string>

namespace mr::python {
namespace {

// The tool's final checks, with its messages: nothing leaves unchecked.
void check_output(const TetMesh& mesh) {
  const check::TetReport quality = check::check_tets(mesh, {.self_intersections = false});
  if (quality.tets == 0)
    throw RunError(
        "no tet lies inside the input (winding number nowhere above 1/2 in magnitude); "
        "filter=False keeps every tet");
  if (!quality.valid())
    throw RunError("the mesh failed its final exact check (" + std::to_string(quality.inverted_tets) +
                   " inverted, " + std::to_string(quality.degenerate_tets) + " flat tets)");
}

// A background tet mesh with a target length per vertex:
// (vertices (P, 3), tets (T, 4), values (P,)).
std::shared_ptr<const ScalarField> sizing_from_object(const py::object& sizing) {
  if (sizing.is_none()) return nullptr;
  const auto parts = py::reinterpret_borrow<py::sequence>(sizing);
  if (!py::isinstance<py::sequence>(sizing) || py::len(parts) != 3)
    throw py::value_error("sizing: expected (vertices, tets, values) of a background tet mesh");
  TetMesh mesh = tet_mesh_from_arrays({parts[0]}, {parts[1]});
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(parts[2]);
  if (!values || values.ndim() != 1 || std::size_t(values.size()) != mesh.positions.size())
    throw py::value_error("sizing: values must be a 1-D array of one length per vertex (" +
                          std::to_string(mesh.positions.size()) + ")");
  mesh.node_fields["values"].assign(values.data(), values.data() + values.size());
  return tetmesh::sizing_from_tet_mesh(std::move(mesh), "sizing");
}

constexpr const char* kDoc =
    R"(Turn any triangle soup into a valid tetrahedral mesh of the solid it describes.

The tetrahedralize tool on arrays: simplify the input inside its epsilon-
envelope, build a background Delaunay mesh, insert every input triangle
exactly, improve the mesh, and keep the tets whose centroid has winding number
|w| > 1/2. Every returned tet is positively oriented on the returned float64
coordinates (exact check).

Args:
    vertices: (N, 3) array of real numbers.
    faces: (M, 3) array of integer vertex indices.
    epsilon: envelope radius relative to the bounding-box diagonal.
    epsilon_abs: absolute envelope radius; overrides epsilon when > 0.
    edge_length: target edge length relative to the bounding-box diagonal.
    edge_length_abs: absolute target edge length; overrides edge_length when > 0.
    lattice: voxel-stuffing lattice spacing relative to the diagonal (0: none).
    lattice_clearance: drop lattice points closer than this (relative to the
        diagonal, > epsilon) to the input.
    stop_energy: improve until the largest AMIPS energy is below this.
    max_passes: at most this many improvement passes (0 skips improvement).
    positive_winding: keep only tets with w > 1/2 (default |w| > 1/2).
    filter: False keeps every tet of the box, labelled by region.
    snap: snap the input to a grid of snap * epsilon before inserting it (0: none).
    skip_simplify: insert the input as it is, without simplifying it first.
    threads: worker threads; 0 uses all hardware threads.
    face_regions: optional int array, one region id per face (e.g. a material).
    labels: how kept tets are labelled: "auto" (by face region when there
        are several, else 1), "regions", "components" (connected parts of
        the input), "winding" (nesting depth) or "none".
    return_labels: also return the int32 label of each tet (its part's with
        the filter, region id + 1 for face regions; the region without it).
    sizing: optional (vertices, tets, values) of a background tet mesh whose
        values (absolute lengths, NaN for none) give the target edge length,
        interpolated linearly (as --sizing FILE).

Returns:
    (vertices, tets), or (vertices, tets, labels) with return_labels: float64
    (N, 3), int64 (K, 4) and int32 (K,) arrays.

Raises:
    ValueError: bad arrays or options.
    meshrepair.Error: nothing to mesh, or a check of the pipeline failed.
)";

}  // namespace

void bind_tetrahedralize(py::module_& m) {
  const tetmesh::TetrahedralizeOptions d;
  m.def(
      "tetrahedralize",
      [](const ArrayLike& vertices, const ArrayLike& faces, double epsilon, double epsilon_abs,
         double edge_length, double edge_length_abs, double lattice, double lattice_clearance,
         double stop_energy, int max_passes, bool positive_winding, bool filter, double snap,
         bool skip_simplify, int threads, const py::object& face_regions, const std::string& labels,
         bool return_labels, const py::object& sizing) -> py::tuple {
        TriangleSoup input = soup_from_arrays(vertices, faces);
        if (!face_regions.is_none())
          input.face_regions = regions_from_array(face_regions, input.triangles.size());
        tetmesh::PipelineOptions options;
        tetmesh::TetrahedralizeOptions& t = options.tetrahedralize;
        t.epsilon_rel = epsilon;
        t.epsilon_abs = epsilon_abs;
        t.edge_length_rel = edge_length;
        t.edge_length_abs = edge_length_abs;
        t.lattice_spacing_rel = lattice;
        t.lattice_clearance_rel = lattice_clearance;
        t.stop_energy = stop_energy;
        t.max_passes = non_negative("max_passes", max_passes);
        t.winding_rule = positive_winding ? tetmesh::WindingRule::positive : tetmesh::WindingRule::absolute;
        t.snap_fraction = snap;
        t.skip_simplify = skip_simplify;
        t.threads = checked_threads(threads);
        options.improve = max_passes > 0;
        options.filter = filter;
        options.labels = tetmesh::tet_labels_named(labels);
        options.sizing = sizing_from_object(sizing);
        const TetMesh mesh = without_gil([&] {
          tetmesh::PipelineResult result = tetmesh::tetrahedralize(input, options);
          check_output(result.mesh);
          return std::move(result.mesh);
        });
        py::tuple arrays = tet_mesh_to_arrays(mesh);
        if (!return_labels) return arrays;
        return py::make_tuple(arrays[0], arrays[1], labels_to_array(mesh.tet_labels));
      },
      kDoc, py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("epsilon") = d.epsilon_rel,
      py::arg("epsilon_abs") = d.epsilon_abs, py::arg("edge_length") = d.edge_length_rel,
      py::arg("edge_length_abs") = d.edge_length_abs, py::arg("lattice") = d.lattice_spacing_rel,
      py::arg("lattice_clearance") = d.lattice_clearance_rel, py::arg("stop_energy") = d.stop_energy,
      py::arg("max_passes") = d.max_passes, py::arg("positive_winding") = false, py::arg("filter") = true,
      py::arg("snap") = d.snap_fraction, py::arg("skip_simplify") = d.skip_simplify,
      py::arg("threads") = d.threads, py::arg("face_regions") = py::none(), py::arg("labels") = "auto",
      py::arg("return_labels") = false, py::arg("sizing") = py::none());
}

}  // namespace mr::python
