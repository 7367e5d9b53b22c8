#pragma once
// Hole filling that changes nothing else: every boundary loop of a surface
// is closed by a patch (Liepa's minimal-dihedral, minimal-area
// triangulation, refined to the density around it and faired), each input
// triangle is kept as it is, and a patch is accepted only if it meets the
// rest of the surface exactly in the loop it closes, checked exactly. A
// patch that fails is retried with other methods (HoleFillOptions).

#include <mr/core/coordinate_grid.h>
#include <mr/core/triangle_soup.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace mr::hole_fill {

/// How smooth a patch meets the surface at its border: not faired (the
/// triangulation as found), tangent-continuous, curvature-continuous.
enum class Fairing { none = 0, tangent = 1, curvature = 2 };

/// keep: new vertices inside the patch at the density of the surrounding
/// surface; coarse: the triangulation of the loop only, no new vertex.
enum class Density { keep, coarse };

struct HoleFillOptions {
  /// Holes with more border edges than this are left open (0: no limit).
  std::size_t max_boundary = 0;
  /// Holes whose border spans more than this (the largest distance between
  /// two of its vertices) are left open.
  double max_diameter = std::numeric_limits<double>::infinity();
  Fairing fairing = Fairing::tangent;
  Density density = Density::keep;
  /// The grid the output is written on: new vertices are checked on it.
  CoordinateGrid grid = CoordinateGrid::doubles();
  /// Stop at the first hole left open (for callers that want every hole
  /// filled or nothing): the holes after it are neither filled nor reported.
  bool stop_at_first_failure = false;
};

enum class HoleOutcome {
  filled,
  too_long,  ///< more border edges than max_boundary
  too_wide,  ///< diameter above max_diameter
  failed,    ///< every method gave a patch that meets the surface elsewhere
};

const char* to_string(HoleOutcome outcome);

struct HoleReport {
  std::size_t border_edges = 0;
  std::size_t islands = 0;  ///< loops of other parts joined into this hole
  double diameter = 0.0;
  HoleOutcome outcome = HoleOutcome::failed;
  std::string method;        ///< the method whose patch was accepted
  std::string why;           ///< failed: why the last patch tried was refused
  std::size_t attempts = 0;  ///< patches tried
  std::size_t patch_faces = 0;
  std::size_t patch_vertices = 0;  ///< new vertices inside the patch
  double seconds = 0.0;
};

struct HoleFillResult {
  /// The input (welded where positions are bit-identical) followed by the
  /// patch faces; input faces keep their order, vertices and positions.
  TriangleSoup surface;
  std::size_t input_faces = 0;  ///< the first input_faces faces of surface are the input's
  /// Border edges on no loop (a path of border edges that cannot close:
  /// it ends where an edge of three or more faces meets the border).
  std::size_t open_border_edges = 0;
  std::vector<HoleReport> holes;

  std::size_t filled() const;
};

/// Fills the holes of `input`. Loops are found on the input welded by
/// identical positions (-0 and +0 alike); a loop that passes a vertex twice
/// (a pinched boundary) is split into simple loops. Holes are filled in parallel (TBB)
/// and accepted in a fixed order, so the result does not depend on the
/// thread count. Attributes are dropped.
HoleFillResult fill_holes(const TriangleSoup& input, const HoleFillOptions& options = {});

}  // namespace mr::hole_fill
