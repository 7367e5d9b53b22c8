#include <mr/plugins/tet_formats.h>

namespace mr::plugins {

void register_tet_formats(io::Registry&) {}  // formats arrive with the plugin's readers and writers

}  // namespace mr::plugins
