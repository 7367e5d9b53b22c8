#pragma once
// The only door to CGAL's Delaunay_triangulation_3 (delaunay.cpp).

#include <mr/core/types.h>

#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// The finite Delaunay tets of `points` (indices into points), in CGAL's
/// iteration order and CGAL's orientation. Points must be distinct.
/// `parallel`: CGAL's TBB insertion with a lock grid over [box_min, box_max],
/// on `threads` threads (0: all).
std::vector<Tet> delaunay_tets(std::span<const Vec3d> points, const Vec3d& box_min, const Vec3d& box_max,
                               bool parallel, int threads);

}  // namespace mr::tetmesh::detail
