#include <mr/plugins/draco_formats.h>

namespace mr::plugins {

void register_draco_formats(io::Registry&) {}  // formats arrive with the plugin's readers and writers

}  // namespace mr::plugins
