#pragma once
// The repair stage of meshrepair (DESIGN.md section 2, stage 7, fast path):
// from the tets the winding-number filter kept to a watertight surface.
//   1. manifold fix: non-manifold edges and vertices of the tets' boundary
//      are resolved geometrically (see manifold_fix.h);
//   2. peel: the boundary of the tets, oriented outward; where the faces
//      tile an input triangle exactly, the triangle goes back in their place
//      (keep_input_triangles);
//   3. clean-up: edge collapses and flips inside the envelope of the
//      ORIGINAL input, vetoing any that leaves it or creates a
//      self-intersection (mr::simplify::simplify_in_envelope_of);
//   4. rounding: every vertex onto the grid the output format stores
//      (float32, Draco's quantization), exactly checked (round_to_grid.h).

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>
#include <mr/repair/manifold_fix.h>
#include <mr/repair/round_to_grid.h>

#include <optional>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace mr::repair {

struct RepairOptions {
  /// Envelope radius, absolute (the pipeline's derived epsilon). > 0.
  double epsilon = 0.0;
  /// Worker threads for the clean-up; 0 means all hardware threads.
  int threads = 0;
  /// Run the clean-up (collapses and flips inside the envelope).
  bool cleanup = true;
  /// Put input triangles the tets did not need to change back as they were
  /// (their corners bit for bit) and keep them through the clean-up, which
  /// then simplifies only the faces around defects and over holes.
  bool keep_input_triangles = false;
  /// With keep_input_triangles: the input as the tets embed it, whose
  /// triangles the peeled faces tile (input positions snapped onto a grid of
  /// inserted_snap_spacing, 0: not snapped); null: the input itself. Must
  /// outlive the call. The corners of the triangles put back go back to the
  /// input's coordinates.
  const TriangleSoup* inserted_input = nullptr;
  double inserted_snap_spacing = 0.0;
  /// Upper bound on the rounds of the manifold fix.
  int max_manifold_rounds = 32;
  /// The grid the output file stores positions on, for a surface inside
  /// [lo, hi] (e.g. mr::io::surface_position_grid). Empty: doubles, no rounding.
  std::function<CoordinateGrid(const Vec3d& lo, const Vec3d& hi)> output_grid;
  /// When no place on the output grid is left for some vertex, a finer grid
  /// for the same box to round onto instead (more Draco bits), or nothing
  /// (the repair then fails). Empty: nothing. Asked before rounding onto
  /// `refused` too (round_to_grid_or_finer), so it must only compute.
  std::function<std::optional<CoordinateGrid>(const Vec3d& lo, const Vec3d& hi,
                                              const CoordinateGrid& refused)>
      finer_output_grid;
  GridRoundingOptions rounding;
};

struct StageTime {
  std::string name;
  double seconds = 0.0;
};

struct RepairResult {
  /// Closed, edge- and vertex-manifold, oriented outward; no two vertices
  /// at the same position.
  TriangleSoup surface;
  ManifoldFixStats manifold;
  std::size_t peeled_faces = 0;  ///< faces of the boundary before the clean-up
  /// Input triangles put back in place of the faces tiling them (keep_input_triangles).
  std::size_t input_triangles_put_back = 0;
  /// The fans of put-back triangles were kept as fans: merging them back
  /// left the rounding to the output grid no room, so the clean-up ran again
  /// without (see repair.cpp, clean_up_and_round).
  bool fan_merges_undone = false;
  std::size_t collapses = 0;
  std::size_t flips = 0;
  /// The grid the surface's positions lie on (the writer must use it).
  CoordinateGrid grid = CoordinateGrid::doubles();
  GridRoundingStats rounding;
  int finer_grids = 0;            ///< grids refused before `grid` (finer_output_grid)
  std::vector<StageTime> stages;  ///< "manifold", "peel", "keep", "cleanup", "round", in order
};

/// Repairs the boundary of the solid made of the tets of `mesh` flagged in
/// `inside` (one flag per tet; empty: every tet) and returns it as a
/// surface. Tets are positively oriented and form an embedding, e.g. the
/// background mesh after insertion, with the winding-number filter's
/// decisions as flags; the rejected tets are there so that the manifold fix
/// can add some of them. `input` is the original input soup whose
/// epsilon-envelope bounds every geometric change. Throws mr::UsageError on
/// bad options, flags or an inconsistent mesh, and mr::RunError when no tet
/// is inside or the surface cannot be made manifold.
RepairResult repair_surface_from_tets(const TetMesh& mesh, std::span<const std::uint8_t> inside,
                                      const TriangleSoup& input, const RepairOptions& options);

}  // namespace mr::repair
