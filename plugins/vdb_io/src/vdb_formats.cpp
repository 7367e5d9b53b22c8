#include <mr/plugins/vdb_formats.h>

#include "vdb_level_set.h"

#include <mr/io/file_bytes.h>

namespace mr::plugins {

void register_vdb_formats(io::Registry& registry) {
  io::Format format = vdb_format_declaration();
  format.read_surface_bytes = [](std::string_view bytes, const std::string& name,
                                 const io::ReadOptions& options) {
    return vdb::read_level_set(bytes, name, options.level_set);
  };
  format.write_surface = [](const TriangleSoup& soup, const std::filesystem::path& path,
                            const io::WriteOptions& options) {
    vdb::write_level_set(soup, path, options.level_set);
  };
  format.read_field = [](const std::filesystem::path& path) {
    const std::vector<char> bytes = io::read_file_bytes(path);
    return vdb::read_scalar_field(std::string_view(bytes.data(), bytes.size()), path.string());
  };
  registry.add(std::move(format));
}

}  // namespace mr::plugins
