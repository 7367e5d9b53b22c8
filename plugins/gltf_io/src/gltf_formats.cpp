#include <mr/plugins/gltf_formats.h>

#include "gltf_reader.h"
#include "gltf_writer.h"

namespace mr::plugins {

void register_gltf_formats(io::Registry& registry) {
  const auto add = [&](const char* name, const char* extension, const char* description, bool glb) {
    io::Format format;
    format.name = name;
    format.extensions = {extension};
    format.kind = io::MeshKind::surface;
    format.description = description;
    format.read_surface_bytes = [glb](std::string_view bytes, const std::string& name,
                                      const io::ReadOptions&) { return gltf::read_gltf(bytes, name, glb); };
    format.write_surface = [glb](const TriangleSoup& soup, const std::filesystem::path& path,
                                 const io::WriteOptions& options) {
      gltf::write_gltf(soup, path, options, glb);
    };
    // Positions are float32 accessors, or Draco's grid with --draco.
    format.position_grid = [](const io::WriteOptions& options, const Vec3d& lo, const Vec3d& hi) {
      if (options.draco.compress_gltf) return io::draco_position_grid(options.draco, lo, hi);
      return options.gltf_position_grid ? *options.gltf_position_grid : CoordinateGrid::float32_over(lo, hi);
    };
    registry.add(std::move(format));
  };
  add("gltf", ".gltf", "glTF 2.0 JSON (buffer embedded as base64; reads external .bin too; --draco)", false);
  add("glb", ".glb", "binary glTF 2.0 (all triangle primitives, node transforms applied; --draco)", true);
}

}  // namespace mr::plugins
