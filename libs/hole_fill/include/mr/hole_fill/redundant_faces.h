#pragma once
// Faces that add nothing to a surface (copies of another face, zero-area
// faces) taken out without moving anything, so that an input whose other
// defects are only holes keeps every other face.

#include <mr/core/triangle_soup.h>

#include <cstddef>

namespace mr::hole_fill {

struct ZeroAreaRemoval {
  /// The surface without them: the same positions; faces in input order,
  /// then the second halves of split faces.
  TriangleSoup surface;
  std::size_t dropped = 0;  ///< zero-area faces taken out
  std::size_t split = 0;    ///< faces split at the middle corner of a collinear face on their edge
  std::size_t left = 0;     ///< collinear faces that could not be taken out (nothing changed for them)
};

/// `welded` (welded by position) with every face over the same three
/// vertices as an earlier face dropped, in either orientation (a copy turned
/// against the kept one is the common case: orient_coherently then decides
/// which way the kept one faces). Returns how many were dropped.
std::size_t remove_repeated_faces(TriangleSoup& welded);

/// Takes the zero-area faces out of `welded` (welded by position: no two
/// vertices share one), exactly and without moving a point of the surface:
/// a face naming a vertex twice is dropped; a face with three collinear
/// corners is dropped and the face across its longest edge split in two at
/// the middle corner, which lay on that edge (a border edge: nothing to
/// split). Faces on a non-manifold edge stop it (the surface comes back with
/// what was done so far), as does a collinear face whose neighbour across
/// that edge is collinear too and stays so (counted in `left`).
ZeroAreaRemoval remove_zero_area_faces(TriangleSoup welded);

}  // namespace mr::hole_fill
