#pragma once
// The faces of a soup a repair must change, and the band around them
// (meshrepair's minimal change simplifies only there before insertion).

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <vector>

namespace mr::tetmesh::detail {

/// One flag per face of `soup`: set on faces that are degenerate (exactly
/// collinear corners), that meet another face away from the vertices and
/// edges they share (exact), or that lie on an edge of other than two faces
/// or whose two faces disagree on orientation (vertices identified by
/// position); then on every face within `rings` vertex rings of those.
std::vector<std::uint8_t> faces_near_defects(const TriangleSoup& soup, int rings);

}  // namespace mr::tetmesh::detail
