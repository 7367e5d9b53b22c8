#pragma once
// meshrepair's way out where rebuilding every face through tets would cost
// too much (tetmesh::RebuildTooCostly): the outer hull of the input on a
// voxel grid (mr/volume/outer_hull.h), which the rebuild then meshes.

#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/options.h>

#include <cstddef>
#include <optional>
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

/// The tet budget of rebuilding every face of an input of `faces` faces:
/// `requested` (--max-tets, max_tets=) when set, else rebuild_tet_budget;
/// 0 (no limit) where this build has no hull to fall back on.
std::size_t rebuild_budget_for(std::size_t faces, std::optional<std::size_t> requested);

/// The options rebuilding the hull of `input` runs with: the input's
/// epsilon (the hull's box is larger), made absolute.
tetmesh::TetrahedralizeOptions hull_rebuild_options(const tetmesh::TetrahedralizeOptions& tetrahedralize,
                                                    const TriangleSoup& input);

/// The hull of `input` with voxels of kHullVoxelsASide along its longest
/// side, but not below epsilon/2 (finer would not bring it within epsilon),
/// and coarser where it would have more than kHullMaxFaces faces (a probe
/// on a coarse grid tells).
OuterHull outer_hull_of(const TriangleSoup& input, double epsilon);

}  // namespace mr::tools
