#pragma once
// Whether a surface needs hole filling only, so that a repair can close its
// holes and keep everything else instead of rebuilding it.

#include <mr/core/triangle_soup.h>

#include <string>

namespace mr::hole_fill {

/// Why `welded` (welded by identical positions: no two vertices share one)
/// has defects other than holes ("faces meet away from their shared
/// vertices and edges", ...), or an empty string when holes are all it lacks
/// to be watertight, or it is watertight already: no degenerate or repeated
/// face, no edge of more than two faces, two-face edges traversed both ways,
/// and no two faces meet except in the vertices and edges they share (exact
/// predicates). A vertex where the border pinches is allowed: filling both
/// holes closes it.
std::string defects_other_than_holes(const TriangleSoup& welded);

}  // namespace mr::hole_fill
