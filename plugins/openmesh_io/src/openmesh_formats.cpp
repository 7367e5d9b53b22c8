#include <mr/plugins/openmesh_formats.h>

namespace mr::plugins {

void register_openmesh_formats(io::Registry&) {}  // formats arrive with the plugin's readers and writers

}  // namespace mr::plugins
