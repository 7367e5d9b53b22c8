#pragma once
// Holes with islands: a part of the surface floating inside a hole (a disk
// left in the middle of an annular gap) has a border loop of its own; the
// hole is the region between the outer loop and the island's, and filling
// each loop on its own would cover the island.

#include "boundary_loops.h"

#include <vector>

namespace mr::hole_fill::detail {

/// A hole: its outer loop and the loops of the islands inside it.
struct Hole {
  BorderLoop outer;
  std::vector<BorderLoop> islands;
};

/// The holes of `loops`, islands joined to the hole around them. A loop B
/// is an island of loop A when B is the only loop of its connected part,
/// that part is another than A's, and, seen along A's mean normal (Newell),
/// every vertex of B's part lies inside A and near A's plane (within A's
/// extent, the diagonal of its box) and B turns the other way round. Loops are
/// otherwise holes of their own, in the order found.
std::vector<Hole> group_islands(const TriangleSoup& welded, std::vector<BorderLoop> loops);

/// The plane a hole is seen in: origin, and unit axes u, v with u x v
/// along the outer loop's Newell normal.
struct HolePlane {
  Vec3d origin, u, v;
  Eigen::Vector2d project(const Vec3d& p) const { return {(p - origin).dot(u), (p - origin).dot(v)}; }
};

HolePlane hole_plane(const TriangleSoup& welded, const BorderLoop& loop);

}  // namespace mr::hole_fill::detail
