#include <mr/io/default_registry.h>
#include <mr/plugins/stl_obj_off_ply_formats.h>
#include <mr/plugins/tet_formats.h>
#ifdef MR_WITH_DRACO
#include <mr/plugins/draco_formats.h>
#endif
#ifdef MR_WITH_GLTF
#include <mr/plugins/gltf_formats.h>
#endif
#ifdef MR_WITH_VDB
#include "lazy_vdb_formats.h"
#endif

namespace mr::io {

Registry make_default_registry() {
  Registry registry;
  plugins::register_stl_obj_off_ply_formats(registry);
  plugins::register_tet_formats(registry);
#ifdef MR_WITH_DRACO
  plugins::register_draco_formats(registry);
#endif
#ifdef MR_WITH_GLTF
  plugins::register_gltf_formats(registry);
#endif
#ifdef MR_WITH_VDB
  // Loaded on first use: OpenVDB costs every process that loads it 26 MB and 30 ms.
  plugins::register_vdb_formats_lazily(registry);
#endif
  return registry;
}

}  // namespace mr::io
