#pragma once
// The boundary of a tet mesh read from a file, for extract-boundary: tets of
// either orientation are accepted (an inverted tet is flipped first, so faces
// always point out of the solid).

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <optional>

namespace mr::repair {

enum class BoundaryMode {
  all,         ///< boundary of every tet
  label,       ///< boundary of the tets with one label
  interfaces,  ///< outer boundary plus every face between tets of different labels
};

struct BoundaryRequest {
  BoundaryMode mode = BoundaryMode::all;
  std::int32_t label = 0;  ///< for BoundaryMode::label
};

/// The requested boundary, oriented outward. Interfaces carry the smaller
/// label of their two tets as face region. Throws mr::UsageError when no tet
/// has the requested label (the message lists the labels present).
TriangleSoup tet_mesh_boundary(const TetMesh& mesh, const BoundaryRequest& request);

/// A copy of `mesh` whose tets all have orient3d >= 0 (exact): inverted tets
/// get two corners swapped. Returns the number flipped through `flipped`.
TetMesh with_positive_tets(const TetMesh& mesh, std::size_t* flipped = nullptr);

}  // namespace mr::repair
