#pragma once
// Stage 6 of the pipeline (paper section 3.3): keep the tets whose centroid
// has generalized winding number above 1/2 with respect to the input soup.
// This is what fills gaps and holes of the input.

#include <mr/core/tet_mesh.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/options.h>
#include <mr/winding_number/winding_number.h>

#include <span>
#include <vector>

namespace mr::tetmesh {

struct TetClassification {
  /// Per tet slot: the winding number at the centroid (0 for removed slots).
  std::vector<double> winding;
  /// Per tet slot: 1 when the tet is kept (never for removed slots).
  std::vector<char> keep;
  std::size_t kept = 0;
};

/// Centroid of a tet, from the double approximations of its corners.
Vec3d tet_centroid(const Mesh& mesh, Index t);

/// Whether a winding number is "inside" under `rule` (w > 1/2, or |w| > 1/2).
bool is_inside(double winding, WindingRule rule);

/// Classifies every live tet (batch evaluation of `tree`, parallel, the same
/// result for any thread count).
TetClassification classify_tets(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule);

/// The tets with keep[t] != 0 and the vertices they use (renumbered in slot
/// order), as doubles. Throws mr::UsageError if keep has the wrong size or
/// keeps a removed slot, mr::RunError if a kept vertex is still rational.
TetMesh extract_tets(const Mesh& mesh, std::span<const char> keep);

}  // namespace mr::tetmesh
