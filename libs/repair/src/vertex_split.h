#pragma once
// Splitting a vertex whose tets fall into several face-connected classes
// (see manifold_fix.h): the geometric resolution of a non-manifold vertex,
// or of both ends of a non-manifold edge.

#include "tet_set.h"

#include <mr/spatial/box_grid.h>

namespace mr::repair::detail {

struct SplitContext {
  TetMesh& mesh;
  const FaceNeighbours& neighbours;  ///< of mesh.tets
  /// One per tet of mesh.tets. A split locks out the rejected tets around
  /// the vertex: they still meet the split classes at the old position.
  std::vector<TetState>& states;
  const std::vector<FaceRef>& boundary;  ///< boundary_faces(neighbours, states)
  double max_move = 0.0;
  /// Indices into `boundary`, each face's box grown by max_move: the box
  /// still covers the face after the moves of one round.
  const spatial::BoxGrid& boundary_grid;
};

/// The grid SplitContext::boundary_grid asks for, for splitting the
/// vertices `to_split` (their stars in `stars`). Holds only the faces a
/// split of those could meet, when they are few.
spatial::BoxGrid grid_of_boundary(const TetMesh& mesh, const std::vector<FaceRef>& boundary, double max_move,
                                  const VertexStars& stars, std::span<const Index> to_split);

/// Gives every class of the solid's tets in `star` (every tet around v) but
/// the largest its own
/// copy of v, moved into the interior of that class's largest tet. A class
/// whose copy finds no valid position (every tet of the class positive, no
/// improper meeting of the new boundary faces with any boundary face, exact)
/// keeps v. Returns the number of copies kept.
std::size_t split_vertex(const SplitContext& context, Index v, std::span<const Index> star);

}  // namespace mr::repair::detail
