#pragma once
// Which faces of a surface meet another one where they should not: the
// exact self-intersection test behind meshrepair's defect band and its
// check of the input triangles it puts back.

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <span>
#include <vector>

namespace mr::spatial {

/// One flag per face of `soup`: whether it meets another face anywhere but
/// in the vertices and edges they share (mr::intersect_triangles, exact;
/// vertices identified by position). Only faces flagged in `asked` are
/// tested (empty: all); faces flagged in `skip` (empty: none) are neither
/// tested nor tested against, and neither are degenerate faces (exactly
/// collinear corners), which have no plane to meet; with `group` (one number per face; empty:
/// none), only faces of another group are tested against. Candidates come
/// from an AABB tree; parallel, deterministic.
std::vector<std::uint8_t> faces_meeting_others(const TriangleSoup& soup,
                                               std::span<const std::uint8_t> asked = {},
                                               std::span<const std::uint8_t> skip = {},
                                               std::span<const std::uint32_t> group = {});

}  // namespace mr::spatial
