#include <mr/plugins/vdb_formats.h>

#include "vdb_level_set.h"

namespace mr::plugins {

void register_vdb_formats(io::Registry& registry) {
  io::Format format;
  format.name = "vdb";
  format.extensions = {".vdb"};
  format.kind = io::MeshKind::surface;
  format.description = "OpenVDB narrow-band level set (mesh <-> signed distance grid)";
  format.read_surface_bytes = [](std::string_view bytes, const std::string& name,
                                 const io::ReadOptions& options) {
    return vdb::read_level_set(bytes, name, options.level_set);
  };
  format.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                            const io::WriteOptions& options) {
    vdb::write_level_set(soup, path, options.level_set);
  };
  registry.add(std::move(format));
}

}  // namespace mr::plugins
