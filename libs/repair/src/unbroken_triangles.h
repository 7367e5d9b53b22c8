#pragma once
// Minimal change (docs/ARCHITECTURE.md, "Keeping the input"): the peeled
// boundary of the tets covers every input triangle away from a defect with
// the many small faces the background mesh cut it into. Where those faces
// tile one input triangle exactly as it was (a disk whose rim runs along
// the triangle's three edges through its three corners, every vertex on
// it), the triangle itself goes back in their place, with its own corners;
// if a neighbour that is not put back still uses points on its edges, it
// goes back as a fan through them instead. Everything else stays as peeled.
// The tets embed the input snapped to a fine grid; a corner whose faces
// are all put back returns to the input's own coordinates.

#include <mr/core/triangle_soup.h>

#include <array>
#include <cstdint>
#include <vector>

namespace mr::repair::detail {

enum class FaceOrigin : std::uint8_t {
  peeled = 0,    ///< a face of the tets' boundary, as peeled
  unbroken = 1,  ///< an input triangle, its corners as the input has them
  fanned = 2,    ///< a piece of an input triangle, fanned through points on its edges
};

struct UnbrokenTriangles {
  TriangleSoup surface;             ///< only the vertices its faces use
  std::vector<FaceOrigin> origins;  ///< one per face of `surface`
  std::size_t put_back = 0;         ///< input triangles put back (whole or fanned)
  /// (point, corner) pairs of vertices of `surface`: each point a fanned
  /// triangle passes through (on its edges, or its centroid) with a corner
  /// of that triangle it may merge into while every face of the fan stays
  /// on the triangle (the corners of the edge it lies on; any corner for
  /// the centroid). The clean-up merges them where the neighbours allow,
  /// which turns the fan back into the triangle.
  std::vector<std::array<Index, 2>> fan_merges;
};

/// `peeled` is a closed, manifold, outward surface without self-
/// intersections (the boundary of positively oriented tets) and `inserted`
/// the soup the tets were built on, with the same coordinates: positions of
/// `input` snapped onto a grid of `snap_spacing` (a power of two; 0: not
/// snapped). A vertex is "on" an inserted triangle when within
/// `tolerance` of it (rounding of cut points; far below epsilon). The
/// result is still closed, manifold and free of self-intersections,
/// decided exactly: a triangle whose replacement meets another face
/// improperly stays as peeled.
UnbrokenTriangles put_back_unbroken_triangles(const TriangleSoup& peeled, const TriangleSoup& inserted,
                                              const TriangleSoup& input, double snap_spacing,
                                              double tolerance);

}  // namespace mr::repair::detail
