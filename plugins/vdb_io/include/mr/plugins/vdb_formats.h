#pragma once

#include <mr/io/registry.h>

namespace mr::plugins {

/// Registers "vdb" (.vdb): surfaces written as narrow-band level sets
/// (signed by the winding number) and read back by meshing the zero level.
void register_vdb_formats(io::Registry& registry);

}  // namespace mr::plugins
