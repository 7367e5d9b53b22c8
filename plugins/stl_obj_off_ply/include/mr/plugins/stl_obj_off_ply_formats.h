#pragma once

#include <mr/io/registry.h>

namespace mr::plugins {

/// Registers this plugin's formats (see the plugin's src/ for the list).
void register_stl_obj_off_ply_formats(io::Registry& registry);

}  // namespace mr::plugins
