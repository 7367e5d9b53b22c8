#pragma once
// The two phases of the simplification, run on a MeshState.

#include "mesh_state.h"

namespace mr::simplify {

/// Greedy edge collapses, cheapest first, until `target_faces` is reached or
/// no candidate passes its checks. Returns the number of collapses.
/// Candidates are popped in batches whose one-rings do not overlap; their
/// checks (envelope and self-intersection included) run in parallel on the
/// surface before the batch, then the batch is applied in cost order,
/// serially, asking the self-intersection test again for a collapse whose
/// one-ring's box meets one of a collapse made before it in the batch. The
/// result is the serial one, whatever the number of threads.
std::size_t collapse_edges(MeshState& state, std::size_t target_faces);

/// Up to `passes` sweeps of angle-improving edge flips over all edges, in
/// index order; checks in parallel, application serial. Returns the number of flips.
std::size_t flip_edges(MeshState& state, int passes);

}  // namespace mr::simplify
