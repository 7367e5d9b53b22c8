#pragma once
// Rounding a hybrid vertex to doubles without inverting any incident tet
// (paper section 3.4). A tet mesh with hybrid vertices calls try_round after
// each operation that creates or moves a rational vertex, and again on the
// remaining rational vertices after their neighbourhood changed.

#include <mr/kernel/hybrid_point.h>

#include <array>
#include <span>

namespace mr {

/// One incident tet seen from the vertex being rounded: the other three
/// corners b, c, d, ordered so that the tet is positively oriented exactly
/// when orient3d(vertex, b, c, d) > 0. opposite_face() builds it from a tet.
using OppositeFace = std::array<const HybridPoint*, 3>;

/// The corners of `tet` other than the one at `corner` (0..3), ordered as
/// OppositeFace requires: orient3d(p[tet[corner]], face...) has the sign of
/// orient3d(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]).
std::array<Index, 3> opposite_face(const Tet& tet, int corner);

/// True when moving `point` to `rounded` keeps every tet of `faces`
/// positively oriented, checked exactly on the other corners' exact positions.
bool keeps_orientation(const Vec3d& rounded, std::span<const OppositeFace> faces);

/// Rounds `point` to its nearest doubles if no incident tet would become
/// inverted or flat; on success the rational part is dropped and true is
/// returned, otherwise the point is left untouched. A point that is already
/// plain doubles returns true.
bool try_round(HybridPoint& point, std::span<const OppositeFace> faces);

/// Convenience for meshes storing hybrid positions by vertex index: rounds
/// positions[vertex] against the tets in `incident_tets` (each must contain
/// `vertex`; otherwise mr::UsageError, raised only when a rational vertex is
/// actually rounded: plain double vertices return true at once).
bool try_round_vertex(std::span<HybridPoint> positions, Index vertex, std::span<const Tet> incident_tets);

}  // namespace mr
