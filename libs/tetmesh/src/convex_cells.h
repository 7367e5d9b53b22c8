#pragma once
// Tetrahedralizing the convex cells that cutting tets by planes creates.
//
// A cell is described by its boundary: planar convex polygons whose corners
// may include flat points (points in the middle of a side, put there by a cut
// of a neighbouring cell). Two cells sharing a polygon must split it the same
// way, so the polygon triangulation below depends only on the polygon (its
// set of corners and their cycle), never on which cell asks or in which
// orientation. Each cell is then filled by a cone from one of its corners
// when a corner sees every boundary triangle it is not on, else from a
// Steiner point inside it.

#include <mr/tetmesh/mesh.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// One boundary triangle of a cell, normal pointing out of the cell, with the
/// input triangle ids of the tracked surface it lies on (empty: untracked).
struct CellTriangle {
  std::array<Index, 3> corners;
  const std::vector<std::uint32_t>* ids = nullptr;
  /// Triangles with the same plane >= 0 lie on one plane (the same face of
  /// the cell): lets the cone test skip exactly coplanar evaluations, which
  /// are the costly ones. -1: unknown.
  int plane = -1;
};

/// A tet made for a cell, and the ids to mark on each of its faces (face k
/// opposite corner k; null: not tracked): its faces on the cell's boundary
/// carry the ids of the boundary triangles they are.
struct ConeTet {
  Tet corners;
  std::array<const std::vector<std::uint32_t>*, 4> face_ids{};
};

/// True when p, q, r lie on a line (exact).
bool collinear(const HybridPoint& p, const HybridPoint& q, const HybridPoint& r);

/// Appends the triangles of the convex polygon `cycle` (planar, at least
/// three non-collinear corners, flat points allowed), oriented as the cycle.
/// Canonical: the same triangles, up to orientation, for any rotation or
/// reversal of the cycle. `sides`, if not empty, gives per cycle entry a bit
/// set of the polygon sides it lies on (a corner two, a flat point one):
/// three entries sharing a side are collinear without an exact evaluation.
void triangulate_convex_polygon(const Mesh& mesh, std::span<const Index> cycle,
                                std::span<const std::uint32_t> sides, std::vector<std::array<Index, 3>>& out);

/// True when every triangle of `boundary` that does not have `apex` as a
/// corner is strictly visible from it: orient3d(apex, triangle) > 0. Then
/// the cone from apex over them fills the region `boundary` encloses (a
/// convex cell, or a star-shaped one such as the star of a vertex).
bool sees_all(const Mesh& mesh, const HybridPoint& apex, Index apex_id,
              std::span<const CellTriangle> boundary);

/// Appends the cone tets from vertex `apex` over the triangles of `boundary`
/// not having it as a corner; the boundary triangles through the apex mark
/// the cone tets' side faces. Precondition: sees_all().
void cone(Index apex, std::span<const CellTriangle> boundary, std::vector<ConeTet>& out);

/// Appends positively oriented tets filling the convex cell bounded by
/// `boundary`, conforming to it. May add one Steiner vertex to `mesh`
/// (returned through `steiner`, kNoVertex otherwise). Throws mr::RunError
/// when no valid filling exists (the boundary is not that of a convex cell).
void tetrahedralize_convex_cell(Mesh& mesh, std::span<const CellTriangle> boundary, std::vector<ConeTet>& out,
                                Index& steiner);

}  // namespace mr::tetmesh::detail
