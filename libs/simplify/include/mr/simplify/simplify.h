#pragma once
// Simplification of a triangle soup inside the epsilon-envelope of the input
// (the preprocessing step of the paper, section 3.4 "Input Simplification"):
// edge collapses ordered by a quadric-plus-length cost, then angle-improving
// edge flips. Every accepted operation keeps each changed triangle inside the
// envelope of the ORIGINAL input, turns no face normal by more than a bound,
// keeps the mesh a valid halfedge mesh (link condition), keeps every vertex
// it removed within epsilon of the faces that are left (so parts thinner than
// epsilon do not erode) and creates no new self-intersection (exact test). Non-manifold parts are kept aside
// untouched; copies of one triangle (double-sided faces) are simplified as one face and written out as often,
// in the same orientations, as the input had them.
//
// Orientation: each patch (faces connected through manifold edges) is first
// oriented coherently, keeping the orientation of the larger part of its area
// (mr::orient_coherently; the first step of tetrahedralize too). A face that
// disagreed with its patch is therefore written reversed: no input face's
// orientation is promised, only that each patch comes out consistently
// oriented, the way most of its area was. Patches are never flipped as a
// whole, so an inward shell (a cavity) stays inward, and copies of a face
// (no manifold edge between them) keep their orientations.

#include <mr/core/triangle_soup.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mr::simplify {

struct SimplifyOptions {
  /// Envelope radius relative to the input's bounding-box diagonal. Used
  /// when epsilon_abs is 0.
  double epsilon_rel = 1e-3;
  /// Absolute envelope radius; overrides epsilon_rel when > 0.
  double epsilon_abs = 0.0;
  /// Stop collapsing at this many output faces (copies and kept-aside faces
  /// included); 0 means as far as the envelope allows.
  std::size_t target_faces = 0;
  /// Largest angle (degrees) between a face's normal before and after an operation.
  double max_normal_deviation_deg = 60.0;
  /// Most sweeps of angle-improving edge flips after the collapses (they stop
  /// at the first sweep that flips nothing); 0 disables them.
  int flip_passes = 20;
  /// Worker threads for the parallel checks; 0 means all hardware threads.
  /// The output does not depend on it.
  int threads = 0;
  /// Empty, or one flag per face of the surface: flagged faces come out as
  /// they went in (their vertices never move; meshrepair's unbroken input
  /// triangles). Collapses and flips change only the other faces.
  std::vector<std::uint8_t> frozen_faces;
  /// Collapses allowed although their vertex is on a frozen face, as
  /// (vertex, into) pairs of indices into the surface's positions: the
  /// vertex may merge into `into`, and along no other edge. The caller
  /// vouches that the frozen faces around it stay on what they stand for
  /// (meshrepair: points a put-back triangle was fanned through merge into
  /// its corners, which turns the fan back into the triangle).
  std::vector<std::array<Index, 2>> frozen_merges;
};

struct SimplifyResult {
  TriangleSoup soup;
  std::size_t faces_before = 0;
  std::size_t faces_after = 0;
  std::size_t kept_aside_faces = 0;  ///< non-manifold or repeated-index faces passed through
  std::size_t duplicate_faces = 0;   ///< copies of an earlier face (same vertices), simplified along with it
  std::size_t reoriented_faces = 0;  ///< faces reversed to orient their patch coherently
  std::size_t locked_vertices = 0;   ///< vertices never moved (non-manifold neighbourhood)
  std::size_t collapses = 0;
  std::size_t flips = 0;
  double epsilon = 0.0;        ///< absolute radius used
  double seconds_setup = 0.0;  ///< weld, halfedge mesh, envelope and grid construction
  double seconds_collapse = 0.0;
  double seconds_flip = 0.0;
};

/// Simplifies `input`. The output keeps the input's vertex positions (a subset
/// of them, after welding bit-identical ones); attributes (normals, UVs,
/// colours, regions) are dropped. Deterministic: the same input and options
/// give the same output whatever the thread count. Throws mr::UsageError on
/// a non-positive epsilon or an inconsistent soup.
SimplifyResult simplify_in_envelope(const TriangleSoup& input, const SimplifyOptions& options = {});

/// The same, but every changed triangle stays inside the envelope of
/// `reference` instead of `surface`'s own: for a surface that a later stage
/// derived from the original input (meshrepair simplifies the peeled boundary
/// of a tet mesh inside the envelope of what the user gave). epsilon_rel is
/// relative to the bounding-box diagonal of `reference`. Throws
/// mr::UsageError as simplify_in_envelope, also for an inconsistent reference.
SimplifyResult simplify_in_envelope_of(const TriangleSoup& surface, const TriangleSoup& reference,
                                       const SimplifyOptions& options = {});

}  // namespace mr::simplify
