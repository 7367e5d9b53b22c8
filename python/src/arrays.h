#pragma once
// NumPy arrays to the library's meshes and back. Input arrays may have any
// real or integer dtype and any strides; they are checked (shape, dtype,
// finite coordinates, indices in range) and py::value_error names the array
// and the problem. Output: float64 (N, 3) positions, int64 (M, 3 or 4) indices.

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace mr::python {

namespace py = pybind11;

/// Any object NumPy can make an array of, checked by the functions below; a
/// type of its own so that signatures read "numpy.typing.ArrayLike".
struct ArrayLike {
  py::object object;
};

TriangleSoup soup_from_arrays(const ArrayLike& vertices, const ArrayLike& faces);
TetMesh tet_mesh_from_arrays(const ArrayLike& vertices, const ArrayLike& tets);

/// (vertices, faces); attributes of the soup are dropped.
py::tuple soup_to_arrays(const TriangleSoup& soup);
/// (vertices, tets).
py::tuple tet_mesh_to_arrays(const TetMesh& mesh);

/// One int32 region id per face from a 1-D integer array of `faces` entries.
std::vector<std::int32_t> regions_from_array(const py::handle& object, std::size_t faces);

/// The per-tet labels as an int32 array.
py::array_t<std::int32_t> labels_to_array(const std::vector<std::int32_t>& labels);

}  // namespace mr::python

namespace pybind11::detail {

template <>
struct type_caster<mr::python::ArrayLike> {
  PYBIND11_TYPE_CASTER(mr::python::ArrayLike, const_name("numpy.typing.ArrayLike"));
  bool load(handle source, bool) {
    value.object = reinterpret_borrow<object>(source);
    return true;
  }
};

}  // namespace pybind11::detail
