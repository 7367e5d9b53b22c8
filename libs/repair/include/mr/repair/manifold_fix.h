#pragma once
// Making the boundary of a set of tets edge- and vertex-manifold. Two parts
// of a solid may touch at a vertex or along an edge; duplicating the vertex
// alone would leave two coincident vertices (what fTetWild's
// --manifold-surface does). Instead, each round:
//   - a vertex whose tets fall into several classes connected through faces
//     is split: every class but the largest gets its own copy of the vertex,
//     moved a short way into the interior of one of its tets. A move is kept
//     only when every tet of the class stays positively oriented and no face
//     of the new boundary meets another face improperly (exact tests);
//   - what a split cannot resolve (a non-manifold edge or vertex whose tets
//     are connected, or a split with no valid move) is resolved by removing
//     the solid's tets of one fan around it, or by adding one fan of the
//     tets the filter rejected there (which joins the fans it lies between),
//     choosing the candidate whose new boundary faces stay inside the
//     envelope, then the smallest volume. Adding matters where two parts
//     of a solid nearly touch: removing a fan there exposes faces far from
//     the input.
// In the first rounds, the tets at each defect are split thin first (a
// collar, collar_width), so the fans removed or added there stay close to
// it. Rounds repeat until the boundary is manifold, at most max_rounds.
//
// Where the rounds run out (or no edit is left), the fix falls back to a
// procedure that always ends manifold: it starts again from the filter's
// tets and, while defects remain, adds every tet around each defect vertex
// to the solid. Each step adds at least one tet (a vertex whose tets are all
// in the solid lies inside it, or on the background mesh's convex hull
// where its boundary faces form a disc, so it is no defect), so it ends
// after at most as many steps as there are tets, at worst with the whole
// background mesh, whose boundary is a closed manifold.

#include <mr/core/tet_mesh.h>
#include <mr/envelope/envelope.h>

#include <cstddef>
#include <cstdint>
#include <span>

namespace mr::repair {

struct ManifoldFixOptions {
  /// Largest distance a split copy of a vertex moves, absolute. > 0.
  double max_move = 0.0;
  /// Before the splits and edits of a round, the tets at each defect
  /// vertex are split so that those touching it lie within this distance
  /// of it (absolute; 0: never): the fans the fix removes or adds there are
  /// then that thin.
  double collar_width = 0.0;
  /// Collars are built in this many first rounds only (manifold_fix.cpp
  /// says why they are rebuilt, and why not for ever).
  int collar_rounds = 10;
  /// Upper bound on rounds; the fallback runs when defects remain after them.
  int max_rounds = 32;
};

struct ManifoldFixStats {
  std::size_t nonmanifold_edges_found = 0;     ///< on the boundary before the fix
  std::size_t nonmanifold_vertices_found = 0;  ///< idem, vertices
  std::size_t collar_splits = 0;               ///< edges split for collars around defects
  std::size_t vertex_copies = 0;               ///< split copies made and moved
  std::size_t removed_tets = 0;
  std::size_t added_tets = 0;  ///< rejected tets added to the solid
  /// New boundary faces left by removals and additions that are not inside
  /// the envelope.
  std::size_t faces_outside_envelope = 0;
  int rounds = 0;
  /// The rounds ran out: the solid was rebuilt from the filter's tets by the fallback.
  bool fell_back = false;
  std::size_t fallback_steps = 0;
  std::size_t fallback_added_tets = 0;
};

/// Edits `mesh` until the boundary of its solid is manifold, and leaves in
/// it the solid's tets only (labels and tagged faces are dropped). `inside`
/// flags the tets of the solid, one per tet, or is empty when every tet is;
/// the others are the tets the winding-number filter rejected, which the
/// fix may add. Tets must be positively oriented and form a valid
/// embedding. `envelope` (may be null) guides the choice of removals and
/// additions. Throws mr::UsageError when `inside` has the wrong size.
ManifoldFixStats make_boundary_manifold(TetMesh& mesh, std::span<const std::uint8_t> inside,
                                        const envelope::Envelope* envelope,
                                        const ManifoldFixOptions& options);

}  // namespace mr::repair
