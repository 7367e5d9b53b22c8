// The plugin module's only exported symbol. The default registry loads the
// module (dlopen) the first time a .vdb file is read or written, so that a
// run which never touches one does not load OpenVDB: its symbol tables alone
// put 26 MB into every process's resident memory and 30 ms into its start.
#include <mr/plugins/vdb_formats.h>

extern "C" __attribute__((visibility("default"))) void mr_register_vdb_formats(mr::io::Registry* registry) {
  mr::plugins::register_vdb_formats(*registry);
}
