// The only exported symbol of libmr_volume.so (outer_hull_module.h).
#include <mr/volume/outer_hull_module.h>

extern "C" __attribute__((visibility("default"))) void mr_outer_hull(
    const mr::TriangleSoup* soup, const mr::volume::OuterHullOptions* options, std::size_t max_voxels,
    mr::TriangleSoup* hull) {
  *hull = mr::volume::outer_hull(*soup, *options, max_voxels);
}
