#pragma once
// The invariant checker of the pipeline's Mesh: what every operation of
// stages 3-6 must preserve. Exact and O(n log n): for tests and debug builds.

#include <mr/tetmesh/mesh.h>

#include <string>

namespace mr::tetmesh {

/// Returns a description of the first violated invariant, or "" when all hold:
/// - every live tet has four distinct live corners;
/// - adjacency is symmetric, neighbours share exactly the face's three
///   corners, no face is shared by more than two tets, and a free face has
///   no twin anywhere (so the free faces are exactly the hull);
/// - every live tet is positively oriented (exact, on hybrid positions), and
///   two neighbours lie on opposite sides of their common face;
/// - surface marks are equal on both sides of a face, and the corners of a
///   marked face are flagged kOnSurface;
/// - a rational position's approx is its nearest double (HybridPoint invariant).
std::string find_mesh_inconsistency(const Mesh& mesh);

/// In debug builds (NDEBUG undefined): throws mr::RunError naming `where`
/// and the first violated invariant. In release builds: does nothing.
void check_in_debug(const Mesh& mesh, const char* where);

}  // namespace mr::tetmesh
