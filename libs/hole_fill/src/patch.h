#pragma once
// One patch for one hole: the triangulation of its border loop, refined and
// faired (CGAL's Polygon Mesh Processing, kept in src/cgal_patch.cpp).

#include <mr/hole_fill/hole_fill.h>

#include <optional>
#include <vector>

namespace mr::hole_fill::detail {

/// How the loop is triangulated (Liepa 2003 in each case: the triangulation
/// of least worst dihedral angle, then least area): in the faces of the 3D
/// Delaunay triangulation of the loop (fast; CGAL falls back to the full
/// search when it holds none), in the full space of triangulations (cubic
/// in the loop's length), or by a constrained Delaunay triangulation in the
/// loop's best-fitting plane (near-planar loops).
enum class Triangulator { delaunay_3d, full_search, plane_2d };

/// The full search is cubic in the loop's length: past this length it is
/// neither a method nor the Delaunay search's fallback (minutes, not seconds).
constexpr std::size_t kCubicSearchMaxLoop = 400;

struct PatchMethod {
  Triangulator triangulator = Triangulator::delaunay_3d;
  bool refine = true;
  Fairing fairing = Fairing::tangent;
};

/// A hole's surroundings in local indices: vertices 0 .. loop_size - 1 are
/// the loop, in the loop's order; `ring` holds input faces around the loop
/// (for the refinement's density and the fairing's continuity) over
/// `positions`.
struct HoleNeighbourhood {
  std::size_t loop_size = 0;
  /// Holes with islands: the islands' loops follow the outer loop's
  /// vertices, `island_sizes` vertices each, and `projected` holds every
  /// loop vertex in the hole's plane (outer loop counter-clockwise); such
  /// a hole is triangulated in that plane whatever the method says.
  std::vector<std::size_t> island_sizes;
  std::vector<Eigen::Vector2d> projected;
  std::vector<Vec3d> positions;
  std::vector<Vec3d> opposite;  ///< per loop edge, the third corner of its input face
  std::vector<Triangle> ring;
};

/// A patch in the neighbourhood's local indices: faces over the loop
/// vertices, the ring vertices and `new_positions` (numbered from
/// positions.size() on), oriented so that loop edge i runs from i to i + 1.
struct Patch {
  std::vector<Vec3d> new_positions;
  std::vector<Triangle> faces;
};

/// The patch `method` makes, or nothing when it finds no triangulation.
std::optional<Patch> make_patch(const HoleNeighbourhood& hole, const PatchMethod& method);

}  // namespace mr::hole_fill::detail
