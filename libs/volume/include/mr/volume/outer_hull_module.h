#pragma once
// outer_hull() from the module libmr_volume.so, loaded on the first call:
// a program that links this instead of mr_volume loads OpenVDB only when it
// computes a hull (meshrepair's fallback, rarely taken).

#include <mr/volume/outer_hull.h>

namespace mr::volume {

/// outer_hull(soup, options, max_voxels), computed by the module. Throws
/// what outer_hull throws, and RunError naming the paths tried when the
/// module cannot be loaded.
TriangleSoup outer_hull_from_module(const TriangleSoup& soup, const OuterHullOptions& options,
                                    std::size_t max_voxels = std::size_t{1} << 28);

}  // namespace mr::volume

/// The module's entry point: *hull = outer_hull(*soup, *options, max_voxels).
extern "C" void mr_outer_hull(const mr::TriangleSoup* soup, const mr::volume::OuterHullOptions* options,
                              std::size_t max_voxels, mr::TriangleSoup* hull);
