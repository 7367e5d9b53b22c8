#pragma once
// meshrepair's way out where rebuilding every face through tets would cost
// too much (tetmesh::RebuildTooCostly): the outer hull of the input on a
// voxel grid (mr/volume/outer_hull.h), which the rebuild then meshes.

#include <mr/core/triangle_soup.h>

#include <string>

namespace mr::tools {

/// Voxels along the longest side of the input's box. The dense flood fill
/// then holds at most 392^3 bytes.
inline constexpr double kHullVoxelsASide = 384.0;

/// The coarse grid whose hull's faces choose the voxel size (1/16 of the
/// cost of 384 a side).
inline constexpr double kHullProbeVoxelsASide = 96.0;

/// Faces of the hull, at most: coarser voxels where a finer grid makes more
/// (a round model of 384 voxels makes about a million). Simplifying them
/// inside the envelope costs about a second per 20,000.
inline constexpr std::size_t kHullMaxFaces = 100'000;

/// The outer hull meshrepair rebuilds instead of its input.
struct OuterHull {
  TriangleSoup surface;
  double voxel_size = 0.0;
  std::string reason;                  ///< the rebuild that cost too much
  double seconds_rebuild_tried = 0.0;  ///< what finding that out cost
  double seconds = 0.0;                ///< making the hull
};

/// Whether this build has the outer hull (OpenVDB).
bool outer_hull_available();

/// The hull of `input` with voxels of kHullVoxelsASide along its longest
/// side, but not below epsilon/2 (finer would not bring it within epsilon),
/// and coarser where it would have more than kHullMaxFaces faces (a probe
/// on a coarse grid tells).
OuterHull outer_hull_of(const TriangleSoup& input, double epsilon);

}  // namespace mr::tools
