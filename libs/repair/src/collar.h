#pragma once
// Thin tets around boundary defects, so that the manifold fix edits stay
// close to them. In a mesh built without a lattice, the tets around a
// non-manifold edge can reach far from it (openscad-nonmanifold-crash:
// removing or adding a fan there left faces 4.5 epsilon from the input).
// Splitting every edge (v, x) at a defect vertex v at distance `width`
// from v leaves every tet at v inside the ball of radius `width` around v
// (a tet is the convex hull of its corners), and every tet at a defect
// edge within `width` of that edge: so are the faces any later fan edit
// exposes there.

#include "tet_set.h"

#include <span>

namespace mr::repair::detail {

/// Splits the edges of `mesh` at the vertices in `centres` (increasing, no
/// repeats) as above; an edge to another centre, an edge no longer than
/// `width`, an edge on the hull of the mesh, and a split that would leave
/// a tet not positively oriented on the doubles (exact test) are left
/// alone. New tets take the state of the tet they were split from and are
/// appended; new vertices are appended. Returns the number of edges split.
std::size_t build_collars(TetMesh& mesh, std::vector<TetState>& states, std::span<const Index> centres,
                          double width);

}  // namespace mr::repair::detail
