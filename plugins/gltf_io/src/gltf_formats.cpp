#include <mr/plugins/gltf_formats.h>

namespace mr::plugins {

void register_gltf_formats(io::Registry&) {}  // formats arrive with the plugin's readers and writers

}  // namespace mr::plugins
