// read(), write(), read_tets(), write_tets(): the formats of the default
// registry (mr/io), chosen by extension unless `format` names one.

#include "arrays.h"
#include "bindings.h"

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <string>

namespace mr::python {
namespace {

namespace fs = std::filesystem;

io::WriteOptions write_options(const std::string& format, bool binary) {
  io::WriteOptions options;
  options.format = format;
  options.binary = binary;
  return options;
}

constexpr const char* kReadDoc = R"(Read a surface file: (vertices, faces).

Any surface format of the build (STL, OBJ, OFF, PLY, glTF/GLB, Draco, VDB), by
extension unless `format` names one ("stl", "glb", ...); a volume file gives
its boundary. Attributes (normals, UVs, colours) are dropped.

Raises:
    meshrepair.InputError: the file cannot be read; the message names it.
)";

constexpr const char* kWriteDoc =
    R"(Write a surface file; the format comes from the extension unless `format` names one.

The file is written to a temporary file and renamed: a failed write never
leaves a half-written file. binary=False writes ASCII where the format has
both (STL, PLY).
)";

constexpr const char* kReadTetsDoc = R"(Read a tet mesh (.msh, .mesh): (vertices, tets).

Raises:
    meshrepair.InputError: the file cannot be read or holds no tet.
)";

constexpr const char* kWriteTetsDoc =
    R"(Write a tet mesh (.msh, .mesh, .vtu); the format comes from the extension.

msh_version: "4.1" or "2.2" for .msh files. binary=False writes ASCII.
)";

}  // namespace

void bind_io(py::module_& m) {
  m.def(
      "read",
      [](const fs::path& path, const std::string& format) {
        const TriangleSoup soup = without_gil([&] {
          io::ReadOptions options;
          options.format = format;
          return io::read_surface(io::make_default_registry(), path, options);
        });
        return soup_to_arrays(soup);
      },
      kReadDoc, py::arg("path"), py::kw_only(), py::arg("format") = "");
  m.def(
      "write",
      [](const fs::path& path, const ArrayLike& vertices, const ArrayLike& faces, bool binary,
         const std::string& format) {
        const TriangleSoup soup = soup_from_arrays(vertices, faces);
        without_gil([&] {
          io::write_surface(io::make_default_registry(), soup, path, write_options(format, binary));
        });
      },
      kWriteDoc, py::arg("path"), py::arg("vertices"), py::arg("faces"), py::kw_only(),
      py::arg("binary") = true, py::arg("format") = "");
  m.def(
      "read_tets",
      [](const fs::path& path, const std::string& format) {
        const TetMesh mesh = without_gil([&] {
          io::ReadOptions options;
          options.format = format;
          return io::read_volume(io::make_default_registry(), path, options);
        });
        return tet_mesh_to_arrays(mesh);
      },
      kReadTetsDoc, py::arg("path"), py::kw_only(), py::arg("format") = "");
  m.def(
      "write_tets",
      [](const fs::path& path, const ArrayLike& vertices, const ArrayLike& tets, bool binary,
         const std::string& msh_version, const std::string& format) {
        const TetMesh mesh = tet_mesh_from_arrays(vertices, tets);
        io::WriteOptions options = write_options(format, binary);
        options.msh_version = msh_version;
        without_gil([&] { io::write_volume(io::make_default_registry(), mesh, path, options); });
      },
      kWriteTetsDoc, py::arg("path"), py::arg("vertices"), py::arg("tets"), py::kw_only(),
      py::arg("binary") = true, py::arg("msh_version") = "4.1", py::arg("format") = "");
}

}  // namespace mr::python
