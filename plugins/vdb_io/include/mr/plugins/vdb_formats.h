#pragma once

#include <mr/io/registry.h>

namespace mr::plugins {

/// Registers "vdb" (.vdb): surfaces written as narrow-band level sets
/// (signed by the winding number) and read back by meshing the zero level.
void register_vdb_formats(io::Registry& registry);

/// The "vdb" format as a registry lists it, without its readers and writers:
/// what a registry can show before the plugin module is loaded.
inline io::Format vdb_format_declaration() {
  io::Format format;
  format.name = "vdb";
  format.extensions = {".vdb"};
  format.kind = io::MeshKind::surface;
  format.description =
      "OpenVDB narrow-band level set (mesh <-> signed distance grid); a float grid as a sizing field";
  return format;
}

}  // namespace mr::plugins

/// The entry point of the plugin module (libmr_vdb_io.so): registers the
/// formats of register_vdb_formats into `registry`.
extern "C" void mr_register_vdb_formats(mr::io::Registry* registry);
