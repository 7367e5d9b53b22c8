#pragma once
// Surfaces exported double-sided: every face written twice, in both
// orientations. Their winding number is 0 everywhere, so the solid they
// bound would vanish in the winding-number filter.

#include <mr/core/triangle_soup.h>

#include <cstddef>

namespace mr {

/// For every connected component (faces sharing an edge, vertices compared
/// by bit-identical position) whose faces are ALL present in both
/// orientations and whose single copies close up (every edge used an even
/// number of times), keeps the first copy of each face and drops the
/// others, then orients the component coherently and outward (positive
/// signed volume). Components with some one-sided face are left alone: a
/// face given in both orientations there is a wall between two touching
/// parts, which must cancel. So are open double-sided sheets: walls of no
/// thickness, which the pipeline thickens. Per-face regions follow their faces. Returns the
/// number of faces dropped. Deterministic.
std::size_t make_double_sided_components_one_sided(TriangleSoup& soup);

/// Drops every face that repeats an earlier one with the same three
/// vertices (bit-identical positions) in the same orientation, keeping the
/// first: a face stored twice would count twice in the winding number and
/// make non-manifold edges that split the patches orientation works on.
/// Copies in the opposite orientation are kept (a wall between two touching
/// parts, or a double-sided sheet). Per-face regions follow their faces.
/// Returns the number dropped.
std::size_t drop_repeated_faces(TriangleSoup& soup);

}  // namespace mr
