#pragma once
// The faces of a surface a repair must change, and the band around them:
// meshrepair's minimal change simplifies only there before insertion, or
// cuts them out and fills the holes they leave.

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <vector>

namespace mr::spatial {

/// One flag per face of `welded` (welded by identical positions): set on
/// faces that are degenerate (exactly collinear corners), that meet another
/// face away from the vertices and edges they share (exact), or that lie on
/// an edge of other than two faces or whose two faces disagree on
/// orientation.
std::vector<std::uint8_t> defect_faces(const TriangleSoup& welded);

/// Sets the flag of every face of `welded` within `rings` vertex rings of a
/// flagged face.
void grow_by_vertex_rings(const TriangleSoup& welded, int rings, std::vector<std::uint8_t>& flags);

/// defect_faces of `soup` welded by identical positions, grown by `rings`
/// vertex rings.
std::vector<std::uint8_t> faces_near_defects(const TriangleSoup& soup, int rings);

}  // namespace mr::spatial
