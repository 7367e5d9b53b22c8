#pragma once
// Removing tets from the solid, or adding rejected ones to it, around a
// non-manifold edge or vertex that splitting could not resolve (see
// manifold_fix.h).

#include "tet_set.h"

#include <mr/envelope/envelope.h>

#include <optional>

namespace mr::repair::detail {

struct SolidEdit {
  std::vector<Index> tets;
  bool add = false;               ///< add rejected tets (else remove kept ones)
  std::size_t faces_outside = 0;  ///< new boundary faces not inside the envelope
  double volume = 0.0;
};

/// Among the edits of `candidates` (each a set of tets, all in the solid or
/// all rejected), the one whose new boundary faces leave the envelope least
/// often (all count as inside when `envelope` is null), then the one that
/// changes the least volume; the first on ties. Candidates that hold a
/// locked-out tet, or that would remove every tet of the solid, are
/// skipped; nullopt when none is left.
std::optional<SolidEdit> choose_edit(const TetMesh& mesh, const FaceNeighbours& neighbours,
                                     std::span<const TetState> states, std::size_t solid_tets,
                                     const std::vector<std::vector<Index>>& candidates,
                                     const envelope::Envelope* envelope);

}  // namespace mr::repair::detail
