// check() and check_tets(): the verdicts of mr::check (the mesh-check tool)
// as dicts with the keys of mesh-check's JSON report.

#include "arrays.h"
#include "bindings.h"
#include "options.h"

#include <mr/check/surface_check.h>
#include <mr/check/tet_check.h>
#include <mr/cli/run_tool.h>

namespace mr::python {
namespace {

py::dict surface_to_dict(const check::SurfaceReport& r) {
  py::dict d;
  d["vertices"] = r.vertices;
  d["faces"] = r.faces;
  d["boundary_edges"] = r.boundary_edges;
  d["nonmanifold_edges"] = r.nonmanifold_edges;
  d["nonmanifold_vertices"] = r.nonmanifold_vertices;
  d["inconsistent_edges"] = r.inconsistent_edges;
  d["degenerate_faces"] = r.degenerate_faces;
  d["duplicate_faces"] = r.duplicate_faces;
  d["components"] = r.components;
  // -1 in the library: not computed.
  d["self_intersecting_pairs"] =
      r.self_intersecting_pairs < 0 ? py::object(py::none()) : py::int_(r.self_intersecting_pairs);
  d["volume"] = r.volume;
  d["closed"] = r.closed();
  d["manifold"] = r.manifold();
  d["watertight"] = r.watertight();
  d["problems"] = check::watertight_failures(r);
  return d;
}

py::dict tets_to_dict(const check::TetReport& r) {
  py::dict d;
  d["vertices"] = r.vertices;
  d["tets"] = r.tets;
  d["inverted_tets"] = r.inverted_tets;
  d["degenerate_tets"] = r.degenerate_tets;
  d["volume"] = r.volume;
  d["min_dihedral_deg"] = r.min_dihedral_deg;
  d["avg_min_dihedral_deg"] = r.avg_min_dihedral_deg;
  d["max_amips"] = r.max_amips;
  d["avg_amips"] = r.avg_amips;
  d["valid"] = r.valid();
  d["boundary"] = surface_to_dict(r.boundary);
  return d;
}

// The library's checks run in parallel (TBB); `threads` bounds them.
template <class Check>
auto run_check(int threads, Check&& check) {
  const int workers = checked_threads(threads);
  return without_gil([&] {
    decltype(check()) report;
    cli::run_with_threads(workers, [&] { report = check(); });
    return report;
  });
}

constexpr const char* kSurfaceDoc = R"(Verify a surface: the verdict of the mesh-check tool.

Positions are welded where bit-identical; degeneracy and self-intersections
are decided exactly.

Args:
    vertices: (N, 3) array of real numbers.
    faces: (M, 3) array of integer vertex indices.
    self_intersections: run the exact self-intersection test (the costly part).
    threads: worker threads; 0 uses all hardware threads.

Returns:
    dict: vertices, faces, boundary_edges, nonmanifold_edges,
    nonmanifold_vertices, inconsistent_edges, degenerate_faces,
    duplicate_faces, components, self_intersecting_pairs (None when not
    computed), volume (signed), closed, manifold, watertight (closed,
    manifold, consistently oriented, outward, no degenerate face, no
    self-intersection) and problems (what keeps it from being watertight).
)";

constexpr const char* kTetsDoc = R"(Verify a tet mesh: the verdict of the mesh-check tool.

Every tet's orientation is decided exactly on the float64 coordinates.

Args:
    vertices: (N, 3) array of real numbers.
    tets: (K, 4) array of integer vertex indices.
    self_intersections: run the exact self-intersection test on the boundary.
    threads: worker threads; 0 uses all hardware threads.

Returns:
    dict: vertices, tets, inverted_tets, degenerate_tets, volume,
    min_dihedral_deg, avg_min_dihedral_deg, max_amips, avg_amips, valid (no
    inverted or flat tet, at least one tet) and boundary (the check() dict of
    the boundary surface).
)";

}  // namespace

void bind_check(py::module_& m) {
  m.def(
      "check",
      [](const ArrayLike& vertices, const ArrayLike& faces, bool self_intersections, int threads) {
        const TriangleSoup soup = soup_from_arrays(vertices, faces);
        return surface_to_dict(run_check(
            threads, [&] { return check::check_surface(soup, {.self_intersections = self_intersections}); }));
      },
      kSurfaceDoc, py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("self_intersections") = true,
      py::arg("threads") = 0);
  m.def(
      "check_tets",
      [](const ArrayLike& vertices, const ArrayLike& tets, bool self_intersections, int threads) {
        const TetMesh mesh = tet_mesh_from_arrays(vertices, tets);
        return tets_to_dict(run_check(
            threads, [&] { return check::check_tets(mesh, {.self_intersections = self_intersections}); }));
      },
      kTetsDoc, py::arg("vertices"), py::arg("tets"), py::kw_only(), py::arg("self_intersections") = true,
      py::arg("threads") = 0);
}

}  // namespace mr::python
