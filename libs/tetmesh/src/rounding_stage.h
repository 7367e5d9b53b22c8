#pragma once
// The end of stage 4: every cut point still rational is rounded to doubles,
// or, when rounding would invert a tet, collapsed onto a nearby neighbour.

#include <mr/tetmesh/mesh.h>

namespace mr::tetmesh::detail {

struct RoundingCounters {
  std::size_t rounded = 0;
  std::size_t collapsed = 0;
  std::size_t remaining = 0;  ///< still rational: the mesh cannot be written
};

/// Rounds or collapses (onto a neighbour closer than `max_collapse_distance`)
/// every rational vertex, repeating while it makes progress. Deterministic.
RoundingCounters round_or_collapse(Mesh& mesh, double max_collapse_distance);

}  // namespace mr::tetmesh::detail
