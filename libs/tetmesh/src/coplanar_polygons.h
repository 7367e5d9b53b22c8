#pragma once
// Groups of input triangles that insertion may embed as one convex polygon.
//
// Where edge-adjacent triangles lie exactly in one plane with the same
// orientation, the edge between them is no feature of the surface: cutting
// the mesh along it (the lines through every triangle edge clip the faces on
// the plane) only fragments it. CAD exports triangulate a planar face with
// long fans whose diagonals cross the whole face; on trimesh/featuretype three
// quarters of all cut points came from such line cuts. Triangles are merged
// greedily into strictly convex polygons, which insertion clips by their
// boundary lines only; the union, its plane and its orientation are exactly
// those of the triangles, so the tracked surface is the same point set and
// the same chain.

#include <mr/tetmesh/mesh.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace mr::tetmesh::detail {

struct ConvexPolygon {
  std::vector<Index> corners;  ///< mesh vertices in the orientation of its triangles
  std::uint32_t id = 0;        ///< the first member triangle: the id its faces are marked with
};

struct CoplanarGrouping {
  std::vector<ConvexPolygon> polygons;  ///< in increasing order of id
  /// Per triangle, the id of the polygon it belongs to (its own id when
  /// alone); kNotGrouped for triangles not eligible.
  std::vector<std::uint32_t> polygon_of;
  static constexpr std::uint32_t kNotGrouped = 0xffffffffu;
};

/// Merges eligible triangles (mesh vertex triples) into strictly convex
/// polygons of at most `max_corners` corners, across edges that exactly two
/// triangles share, in opposite directions, with the fourth corner exactly on
/// the plane. Deterministic: triangles are taken in index order, each
/// polygon grows across its edges in order. Every decision is exact.
CoplanarGrouping group_coplanar_triangles(const Mesh& mesh, std::span<const std::array<Index, 3>> triangles,
                                          std::span<const char> eligible, std::size_t max_corners);

}  // namespace mr::tetmesh::detail
