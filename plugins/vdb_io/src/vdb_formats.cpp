#include <mr/plugins/vdb_formats.h>

namespace mr::plugins {

void register_vdb_formats(io::Registry&) {}  // formats arrive with the plugin's readers and writers

}  // namespace mr::plugins
