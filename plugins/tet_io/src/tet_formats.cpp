#include <mr/plugins/tet_formats.h>

#include "tet_formats_internal.h"

namespace mr::plugins {

void register_tet_formats(io::Registry& registry) {
  io::Format msh;
  msh.name = "msh";
  msh.extensions = {".msh"};
  msh.kind = io::MeshKind::volume;
  msh.description = "Gmsh MSH 4.1 or 2.2, ASCII or binary (tets, triangles; labels as physical tags)";
  msh.read_volume_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return tet::read_msh(bytes, name);
  };
  msh.write_volume = tet::write_msh;
  registry.add(std::move(msh));

  io::Format medit;
  medit.name = "mesh";
  medit.extensions = {".mesh"};
  medit.kind = io::MeshKind::volume;
  medit.description = "Medit / INRIA mesh, ASCII (tets, triangles; labels as references)";
  medit.read_volume_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return tet::read_medit(bytes, name);
  };
  medit.write_volume = [](const TetMesh& mesh, const std::filesystem::path& path, const io::WriteOptions&) {
    tet::write_medit(mesh, path);
  };
  registry.add(std::move(medit));

  io::Format vtu;
  vtu.name = "vtu";
  vtu.extensions = {".vtu"};
  vtu.kind = io::MeshKind::volume;
  vtu.description = "VTK XML unstructured grid (tets with a \"label\" cell array), write only";
  vtu.write_volume = tet::write_vtu;
  registry.add(std::move(vtu));
}

}  // namespace mr::plugins
