#include "bindings.h"

#include <mr/core/errors.h>

namespace mr::python {

// The messages are the ones the tools print after "tool: error: ".
// pybind11 tries translators from the last registered, so the most derived
// C++ types are registered last.
void register_errors(py::module_& m) {
  const auto error = py::register_exception<mr::Error>(m, "Error", PyExc_RuntimeError);
  error.doc() = "A run that could not complete (the tools' exit code 1). Subclass of RuntimeError.";
  const auto input_error = py::register_exception<mr::InputError>(m, "InputError", error.ptr());
  input_error.doc() = "A file that cannot be read as the mesh it claims to be; the message names the file.";
  // Bad options are the caller's values: Python's ValueError, as for bad arrays.
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const mr::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace mr::python
