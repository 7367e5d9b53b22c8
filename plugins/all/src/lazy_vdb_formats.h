#pragma once
// The "vdb" format of the default registry, whose readers and writers load
// the OpenVDB plugin module (libmr_vdb_io.so) on first use.

#include <mr/io/registry.h>

namespace mr::plugins {

/// Registers "vdb" with the name, extensions and description of the plugin;
/// its first read or write loads the module and forwards to the module's
/// format from then on. A read or write throws RunError naming the paths
/// tried if the module cannot be loaded.
void register_vdb_formats_lazily(io::Registry& registry);

}  // namespace mr::plugins
