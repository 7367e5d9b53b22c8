#pragma once
// Conversion between the pipeline's Mesh and the plain mr::TetMesh that
// writers and checks take.

#include <mr/core/tet_mesh.h>
#include <mr/tetmesh/mesh.h>

namespace mr::tetmesh {

/// Builds a Mesh (double positions, no flags, no marks) with its adjacency.
/// Throws mr::UsageError on an index out of range, a repeated corner or a
/// face shared by more than two tets. Orientation is not checked here.
Mesh from_tet_mesh(const TetMesh& input);

/// The live vertices (in slot order) and live tets of `mesh`, as doubles.
/// Removed slots are skipped, so indices are those compact() would give.
/// Throws mr::RunError when a live vertex still holds a rational position:
/// rounding it now could invert a tet, the writer must never see that.
TetMesh to_tet_mesh(const Mesh& mesh);

}  // namespace mr::tetmesh
