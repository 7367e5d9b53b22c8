#pragma once
// Stage 6 of the pipeline (paper section 3.3): keep the tets whose centroid
// has generalized winding number above 1/2 with respect to the input soup.
// This is what fills gaps and holes of the input.

#include <mr/core/tet_mesh.h>
#include <mr/envelope/envelope.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/open_surface_winding.h>
#include <mr/tetmesh/options.h>
#include <mr/winding_number/winding_number.h>

#include <array>
#include <map>
#include <span>
#include <vector>

namespace mr::tetmesh {

struct TetClassification {
  /// Per tet slot: the winding number at the centroid (0 for removed slots).
  std::vector<double> winding;
  /// Per tet slot: 1 when the tet is kept (never for removed slots).
  std::vector<char> keep;
  std::size_t kept = 0;
};

/// Centroid of a tet, from the double approximations of its corners.
Vec3d tet_centroid(const Mesh& mesh, Index t);
/// Six times a tet's signed volume, from the double approximations of its corners.
double tet_approx_volume6(const Mesh& mesh, Index t);

/// Whether a winding number is "inside" under `rule` (w > 1/2, or |w| > 1/2).
bool is_inside(double winding, WindingRule rule);

/// Classifies every live tet (batch evaluation of `tree`, parallel, the same
/// result for any thread count).
TetClassification classify_tets(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule);

/// Classifies every live tet by the winding number `winding[t]` given per
/// tet slot (for instance decided before improvement and carried through it).
TetClassification classify_by_winding(const Mesh& mesh, std::span<const double> winding, WindingRule rule);

/// How far the tracked surface strayed from each input triangle: per
/// triangle of `input`, the largest distance of a vertex of a tracked face
/// carrying its id from its plane (doubles). Rounding moves cut points by
/// about an ulp; collapses of unroundable points and mesh improvement move
/// them further.
std::vector<double> tracked_surface_offsets(const Mesh& mesh, const TriangleSoup& input);

/// Classifies every live tet by the winding number of the tracked surface
/// (whose tree is `tracked`) at its centroid, for when it is not a cycle
/// (an open input, or triangles left out), asked of the input triangles it embeds (left_out[i] == 0) wherever
/// the two cannot differ much: the tracked chain is those triangles cut into faces, each moved off its
/// triangle by at most that triangle's offset
/// (`offsets`, from tracked_surface_offsets), so at a centroid farther than kOffsetMargin
/// times the offset from every triangle both numbers agree to a small
/// fraction. The input has far fewer and better shaped triangles than the
/// tracked surface of a fragmented mesh, whose long thin faces made each
/// query near the surface descend to hundreds of leaves (thingi10k/1514499:
/// 96 s for 1.8M tets). Centroids nearer than that ask `tracked`.
inline constexpr double kOffsetMargin = 16.0;
TetClassification classify_tets_near_input(const Mesh& mesh, const WindingNumberTree& tracked,
                                           const TriangleSoup& input, std::span<const char> left_out,
                                           std::span<const double> offsets, WindingRule rule,
                                           std::size_t* near_queries = nullptr);
/// Per tet slot, the winding number at the centroids of the tracked surface
/// `tracked` (a chain whose triangle i is the mesh face origins[i]) when it
/// is no cycle. Carried from tet to tet by counting crossings
/// (open_surface_winding.h) when its boundary has no more edges than `input`
/// has triangles not left out; else asked tet by tet of the input and, near
/// where the tracked faces strayed, of `tracked` (classify_tets_near_input).
/// The triangles that cap the boundary are asked at every tet: a boundary of
/// many short edges (trimesh/soup, 100 large crossing triangles cut into
/// 31k boundary edges) made that cost more than asking the input.
struct OpenSurfaceStats {
  bool by_crossings = false;
  OpenWindingStats crossings;
  std::size_t near_queries = 0;
};
std::vector<double> open_tracked_winding(const Mesh& mesh, const TriangleSoup& tracked,
                                         std::span<const FaceRef> origins, std::size_t boundary_edges,
                                         const TriangleSoup& input, std::span<const char> left_out,
                                         OpenSurfaceStats& stats);

/// Per tet slot, 1 for the live tets that may meet a triangle of
/// `triangles` (their bounding sphere, doubled, reaches one).
std::vector<char> tets_near(const Mesh& mesh, const TriangleSoup& triangles);

/// The winding-number filter decided once per region (tets connected
/// through faces that are not tracked surface; a tet with barrier[t] != 0
/// is a region of its own), at the centroid of its largest tet (ties: the smallest slot). Equal to
/// classify_tets when `tree` is built on a tracked surface that is a cycle,
/// and far cheaper: most tets lie near the surface, where each query
/// descends to the triangles. Also sound when `tree` is built on a closed
/// input some of whose triangles were left out (so the tracked surface has
/// holes), with the tets near those triangles as `barrier`: they plug the
/// holes between regions, and each is decided at its own centroid.
/// `cache`, when given, keeps the winding number of every point asked, so
/// that classifying again after local edits asks only the new points.
using WindingCache = std::map<std::array<double, 3>, double>;
TetClassification classify_regions(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule,
                                   std::span<const char> barrier = {}, WindingCache* cache = nullptr);

struct BarrierRefinementOptions {
  /// Rounds of classify, find faces outside, split; each splits (about
  /// halves) the tets that made such faces.
  int max_rounds = 40;
};

struct BarrierRefinementStats {
  int rounds = 0;
  std::size_t splits = 0;
  std::size_t barrier_tets = 0;   ///< in the last classification
  std::size_t faces_outside = 0;  ///< boundary faces outside the envelope after the last round
};

/// classify_regions for a closed input with triangles left out (`holes`),
/// the tets near them as barriers, made to keep the output boundary in the
/// envelope. A barrier tet that straddles the input is kept or removed
/// whole, so the boundary may run along its far faces. While some face
/// between a kept and a removed tet (or the hull) is neither tracked nor
/// inside `envelope` and a barrier tet is on either side, the longest edge
/// of that tet that can be split (positive tets, tracked halves inside the
/// envelope) is split at its midpoint and the tets are classified again.
/// Sequential, in slot order: deterministic.
TetClassification classify_with_refined_barrier(Mesh& mesh, const TriangleSoup& holes,
                                                const WindingNumberTree& tree, WindingRule rule,
                                                const envelope::Envelope& envelope,
                                                const BarrierRefinementOptions& options,
                                                BarrierRefinementStats& stats);

/// The tets with keep[t] != 0 and the vertices they use (renumbered in slot
/// order), as doubles. Throws mr::UsageError if keep has the wrong size or
/// keeps a removed slot, mr::RunError if a kept vertex is still rational.
TetMesh extract_tets(const Mesh& mesh, std::span<const char> keep);

}  // namespace mr::tetmesh
