#pragma once
// Helpers of the pipeline's last stages: region labels for unfiltered
// output, the tracked surface as a soup, and the final exact check.

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/mesh.h>

#include <span>
#include <vector>

namespace mr::tetmesh::detail {

/// Per tet slot, a label numbering the sets of tets connected through faces
/// that are not tracked surface: 1, 2, ... in order of their smallest tet
/// slot; 0 for removed slots.
std::vector<std::int32_t> region_labels(const Mesh& mesh);

/// The tracked-surface faces of the tets with keep[t] != 0 (every live tet
/// when keep is empty), each once, oriented like the input triangle of its
/// smallest id, with its own vertices (doubles: call after rounding).
TriangleSoup tracked_surface(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input);

/// The number of tets of `mesh` that are not strictly positively oriented
/// on their double coordinates (exact orient3d; parallel).
std::size_t count_non_positive_tets(const TetMesh& mesh);

}  // namespace mr::tetmesh::detail
