#include <mr/core/plugin_module.h>
#include <mr/volume/outer_hull_module.h>

namespace mr::volume {

TriangleSoup outer_hull_from_module(const TriangleSoup& soup, const OuterHullOptions& options,
                                    std::size_t max_voxels) {
  // Loading an already loaded module only finds it again: no state to keep.
  PluginModule module("libmr_volume.so", MR_VOLUME_MODULE_BUILD_PATH);
  const auto entry = reinterpret_cast<decltype(&mr_outer_hull)>(module.symbol("mr_outer_hull"));
  TriangleSoup hull;
  entry(&soup, &options, max_voxels, &hull);
  return hull;
}

}  // namespace mr::volume
