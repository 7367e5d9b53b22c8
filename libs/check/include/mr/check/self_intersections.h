#pragma once
// Exact self-intersection count of a triangle soup.

#include <mr/core/triangle_soup.h>

#include <cstdint>

namespace mr::check {

/// Pairs of faces that meet anywhere except along what they share: faces
/// sharing one vertex must meet only there, faces sharing an edge only along
/// it (coplanar faces folding onto each other count), and faces sharing three
/// vertices (duplicates) always count. Vertices are identified by position.
/// Degenerate faces (exactly collinear corners) are skipped: they are counted
/// as degenerate by check_surface. All decisions use exact predicates.
std::int64_t count_self_intersections(const TriangleSoup& soup);

}  // namespace mr::check
