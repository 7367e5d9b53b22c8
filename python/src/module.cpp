// The Python module `meshrepair`: the toolkit's tools as functions on NumPy arrays.

#include "bindings.h"

#include <mr/cli/run_tool.h>

PYBIND11_MODULE(meshrepair, m) {
  namespace python = mr::python;
  m.doc() = R"(Robust mesh repair and tetrahedral meshing on NumPy arrays.

The functions of the command-line tools, on arrays: vertices are (N, 3) real
numbers (float64 inside), faces (M, 3) and tets (K, 4) integer vertex indices.
Each function releases the GIL while it works. Bad arrays or options raise
ValueError; a run that cannot complete raises meshrepair.Error (a
RuntimeError) with the message the tool prints.

    repair          any surface -> watertight surface      (meshrepair)
    tetrahedralize  surface -> valid tet mesh              (tetrahedralize)
    simplify        fewer faces within epsilon             (simplify-in-envelope)
    fill_holes      holes closed, everything else kept     (hole-fill)
    check, check_tets   verdicts                           (mesh-check)
    read, write, read_tets, write_tets   files, format by extension
)";
  m.attr("__version__") = mr::cli::version_string();
  python::register_errors(m);
  python::bind_repair(m);
  python::bind_tetrahedralize(m);
  python::bind_simplify(m);
  python::bind_hole_fill(m);
  python::bind_check(m);
  python::bind_io(m);
}
