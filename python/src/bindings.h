#pragma once
// The parts of the Python module, one function per area, each adding its
// functions to the module. Every function converts its arrays with the GIL
// held, runs the library without it (other Python threads keep running, and
// two calls can run at once), and converts the result back with it.

#include <pybind11/pybind11.h>

#include <utility>

namespace mr::python {

namespace py = pybind11;

/// Maps the library's typed exceptions to Python ones (errors.cpp).
void register_errors(py::module_& m);

void bind_repair(py::module_& m);
void bind_tetrahedralize(py::module_& m);
void bind_simplify(py::module_& m);
void bind_hole_fill(py::module_& m);
void bind_check(py::module_& m);
void bind_io(py::module_& m);

/// Runs `work` with the GIL released; it must not touch Python objects.
/// An exception leaves after the GIL is taken back, so it can be translated.
template <class Work>
auto without_gil(Work&& work) {
  py::gil_scoped_release release;
  return std::forward<Work>(work)();
}

}  // namespace mr::python
