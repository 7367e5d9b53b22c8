#pragma once

#include <mr/io/registry.h>

namespace mr::plugins {

/// Registers this plugin's formats (see the plugin's src/ for the list).
void register_vdb_formats(io::Registry& registry);

}  // namespace mr::plugins
