// Registers STL, OBJ, OFF and PLY. Every reader builds the TriangleSoup
// directly (no halfedge structure in between), so non-manifold, duplicate and
// degenerate faces and isolated vertices are kept. Each format's file says why
// it has its own parser rather than OpenMesh's reader; in short: OpenMesh's
// readers feed a halfedge-oriented importer, trust header counts, report
// problems on a global log stream instead of failing, and read PLY positions
// as float.

#include <mr/plugins/stl_obj_off_ply_formats.h>

#include "formats.h"

namespace mr::plugins {
namespace {

using namespace stl_obj_off_ply;

io::Format surface_format(std::string name, std::string extension, std::string description) {
  io::Format format;
  format.name = std::move(name);
  format.extensions = {std::move(extension)};
  format.kind = io::MeshKind::surface;
  format.description = std::move(description);
  return format;
}

}  // namespace

void register_stl_obj_off_ply_formats(io::Registry& registry) {
  io::Format stl = surface_format("stl", ".stl", "STL, binary (default) or ASCII; corners welded on read");
  stl.read_surface_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return read_stl(bytes, name);
  };
  stl.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions& options) { write_stl(soup, path, options.binary); };
  stl.position_grid = [](const io::WriteOptions&, const Vec3d&, const Vec3d&) {
    return CoordinateGrid::float32();
  };
  registry.add(std::move(stl));

  io::Format obj =
      surface_format("obj", ".obj", "Wavefront OBJ with normals, uvs, usemtl regions and MTL materials");
  obj.read_surface_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return read_obj(bytes, name);
  };
  obj.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions& options) { write_obj(soup, path, options.destination); };
  registry.add(std::move(obj));

  io::Format off = surface_format("off", ".off", "Object File Format (OFF, COFF, NOFF, STOFF)");
  off.read_surface_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return read_off(bytes, name);
  };
  off.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions&) { write_off(soup, path); };
  registry.add(std::move(off));

  io::Format ply = surface_format("ply", ".ply", "Stanford PLY, binary little endian (default) or ASCII");
  ply.read_surface_bytes = [](std::string_view bytes, const std::string& name, const io::ReadOptions&) {
    return read_ply(bytes, name);
  };
  ply.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                         const io::WriteOptions& options) { write_ply(soup, path, options.binary); };
  registry.add(std::move(ply));
}

}  // namespace mr::plugins
