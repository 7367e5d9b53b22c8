#include "arrays.h"

#include <cstdint>
#include <limits>
#include <string>

namespace mr::python {
namespace {

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) text += (d ? ", " : "") + std::to_string(a.shape(d));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

// The array `object` is, or converts to, with `columns` columns and a dtype
// of one of the numpy kinds in `kinds` ('f' float, 'i' signed, 'u' unsigned).
py::array checked_array(const py::handle& object, const char* name, py::ssize_t columns,
                        const std::string& kinds, const char* what) {
  py::array a = py::array::ensure(object);
  if (!a) throw py::value_error(std::string(name) + " must be an array of " + what);
  if (kinds.find(a.dtype().kind()) == std::string::npos)
    throw py::value_error(std::string(name) + " must be an array of " + what + ", got dtype " +
                          std::string(py::str(a.dtype())));
  if (a.ndim() != 2 || a.shape(1) != columns)
    throw py::value_error(std::string(name) + " must have shape (N, " + std::to_string(columns) + "), got " +
                          shape_text(a));
  return a;
}

std::vector<Vec3d> positions_from_array(const py::handle& object) {
  // Integer coordinates are exact in doubles; any float dtype converts.
  const py::array a = checked_array(object, "vertices", 3, "fiu", "real numbers");
  const auto values = py::array_t<double, py::array::forcecast>::ensure(a);
  if (!values) throw py::value_error("vertices cannot be converted to float64");
  const auto v = values.unchecked<2>();
  std::vector<Vec3d> positions(static_cast<std::size_t>(v.shape(0)));
  for (py::ssize_t i = 0; i < v.shape(0); ++i) {
    positions[i] = Vec3d(v(i, 0), v(i, 1), v(i, 2));
    if (!positions[i].allFinite())
      throw py::value_error("vertices[" + std::to_string(i) + "] is not finite (NaN or infinity)");
  }
  return positions;
}

// Rows of K vertex indices, each in [0, vertex_count).
template <std::size_t K>
std::vector<std::array<Index, K>> cells_from_array(const py::handle& object, const char* name,
                                                   std::size_t vertex_count) {
  const py::array a = checked_array(object, name, K, "iu", "integers");
  const auto values = py::array_t<std::int64_t, py::array::forcecast>::ensure(a);
  if (!values) throw py::value_error(std::string(name) + " cannot be converted to int64");
  const auto c = values.unchecked<2>();
  std::vector<std::array<Index, K>> cells(static_cast<std::size_t>(c.shape(0)));
  for (py::ssize_t i = 0; i < c.shape(0); ++i) {
    for (std::size_t k = 0; k < K; ++k) {
      const std::int64_t index = c(i, k);
      if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count)
        throw py::value_error(std::string(name) + "[" + std::to_string(i) + ", " + std::to_string(k) +
                              "] = " + std::to_string(index) + " is not a vertex index (there are " +
                              std::to_string(vertex_count) + " vertices)");
      cells[i][k] = static_cast<Index>(index);
    }
  }
  return cells;
}

std::vector<Vec3d> checked_positions(const py::handle& vertices) {
  std::vector<Vec3d> positions = positions_from_array(vertices);
  if (positions.size() > std::numeric_limits<Index>::max())
    throw py::value_error("more vertices than 32-bit indices can address");
  return positions;
}

py::array_t<double> positions_to_array(const std::vector<Vec3d>& positions) {
  py::array_t<double> array({static_cast<py::ssize_t>(positions.size()), py::ssize_t{3}});
  auto v = array.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i)
    for (py::ssize_t k = 0; k < 3; ++k) v(i, k) = positions[i][k];
  return array;
}

template <std::size_t K>
py::array_t<std::int64_t> cells_to_array(const std::vector<std::array<Index, K>>& cells) {
  py::array_t<std::int64_t> array({static_cast<py::ssize_t>(cells.size()), static_cast<py::ssize_t>(K)});
  auto c = array.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < c.shape(0); ++i)
    for (std::size_t k = 0; k < K; ++k) c(i, k) = cells[i][k];
  return array;
}

}  // namespace

std::vector<std::int32_t> regions_from_array(const py::handle& object, std::size_t faces) {
  const py::array a = py::array::ensure(object);
  if (!a || std::string("iu").find(a.dtype().kind()) == std::string::npos || a.ndim() != 1)
    throw py::value_error("face_regions must be a 1-D array of integers");
  if (static_cast<std::size_t>(a.shape(0)) != faces)
    throw py::value_error("face_regions has " + std::to_string(a.shape(0)) + " entries for " +
                          std::to_string(faces) + " faces");
  const auto values = py::array_t<std::int64_t, py::array::forcecast>::ensure(a);
  const auto r = values.unchecked<1>();
  std::vector<std::int32_t> regions(faces);
  for (py::ssize_t i = 0; i < r.shape(0); ++i) {
    if (r(i) < 0 || r(i) > std::numeric_limits<std::int32_t>::max() - 1)
      throw py::value_error("face_regions[" + std::to_string(i) + "] = " + std::to_string(r(i)) +
                            " is not a region id (0 to 2^31 - 2)");
    regions[i] = static_cast<std::int32_t>(r(i));
  }
  return regions;
}

TriangleSoup soup_from_arrays(const ArrayLike& vertices, const ArrayLike& faces) {
  TriangleSoup soup;
  soup.positions = checked_positions(vertices.object);
  soup.triangles = cells_from_array<3>(faces.object, "faces", soup.positions.size());
  return soup;
}

TetMesh tet_mesh_from_arrays(const ArrayLike& vertices, const ArrayLike& tets) {
  TetMesh mesh;
  mesh.positions = checked_positions(vertices.object);
  mesh.tets = cells_from_array<4>(tets.object, "tets", mesh.positions.size());
  return mesh;
}

py::tuple soup_to_arrays(const TriangleSoup& soup) {
  return py::make_tuple(positions_to_array(soup.positions), cells_to_array(soup.triangles));
}

py::tuple tet_mesh_to_arrays(const TetMesh& mesh) {
  return py::make_tuple(positions_to_array(mesh.positions), cells_to_array(mesh.tets));
}

py::array_t<std::int32_t> labels_to_array(const std::vector<std::int32_t>& labels) {
  return py::array_t<std::int32_t>(static_cast<py::ssize_t>(labels.size()), labels.data());
}

}  // namespace mr::python
