#pragma once
// Coherent orientation of a triangle soup: faces that share a manifold edge
// should run along it in opposite directions. Scans and hand-made models
// often have a few faces flipped; the winding number of such a surface dips
// towards 0 inside the solid next to them and reaches 1 outside, so the
// filter of the pipeline would cut holes. Orienting first removes that.

#include <mr/core/triangle_soup.h>

#include <cstddef>
#include <span>

namespace mr {

struct OrientationStats {
  std::size_t patches = 0;    ///< sets of faces connected through manifold edges
  std::size_t flipped = 0;    ///< faces whose orientation was reversed
  std::size_t conflicts = 0;  ///< manifold edges left inconsistent (non-orientable patch)
};

/// Makes every patch (faces connected through edges with exactly two faces,
/// vertices compared by bit-identical position) consistently oriented, keeping the
/// orientation of the larger part of its area. Patches are never flipped as
/// a whole, so an intentionally inverted shell (a cavity) stays inverted.
/// Non-manifold edges, boundary edges, faces with a repeated corner and
/// edges shared only by two copies of one triangle are
/// left as they are. Deterministic; no floating-point test decides topology
/// (areas only break the tie of which orientation a patch keeps).
OrientationStats orient_coherently(TriangleSoup& soup);

/// The same, with the evidence for each face's present orientation given
/// by the caller: votes[f] > 0 says face f is probably right as it is, < 0
/// that it is probably wrong, its magnitude how sure. Each patch keeps the
/// orientation with the larger total. votes.size() == soup.triangles.size().
OrientationStats orient_coherently(TriangleSoup& soup, std::span<const double> votes);

}  // namespace mr
