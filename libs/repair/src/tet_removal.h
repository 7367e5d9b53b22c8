#pragma once
// Removing tets around a non-manifold edge or vertex that splitting could not
// resolve (see manifold_fix.h).

#include "tet_set.h"

#include <mr/envelope/envelope.h>

#include <cstdint>
#include <optional>

namespace mr::repair::detail {

struct RemovalChoice {
  std::vector<Index> tets;
  std::size_t faces_outside = 0;  ///< new boundary faces not inside the envelope
  double volume = 0.0;
};

/// Among `candidates` (sets of tets not yet removed), the one whose removal
/// exposes the fewest faces outside the envelope (all count as inside when
/// `envelope` is null), then the one of least volume; the first on ties.
/// Candidates that would remove every remaining tet are skipped; nullopt
/// when none is left.
std::optional<RemovalChoice> choose_removal(const TetMesh& mesh, const FaceNeighbours& neighbours,
                                            const std::vector<std::uint8_t>& removed, std::size_t remaining,
                                            const std::vector<std::vector<Index>>& candidates,
                                            const envelope::Envelope* envelope);

}  // namespace mr::repair::detail
