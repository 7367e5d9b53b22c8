#pragma once
// Stage 5 of the pipeline (paper section 3.2): mesh improvement. Local
// operations (edge split, edge collapse, 3-2 / 2-3 / 4-4 swaps, vertex
// smoothing) lower the conformal AMIPS energy and bring edges towards the
// target length. Every operation keeps the contract of the Mesh:
// - all tets stay strictly positive (exact orient3d on the hybrid positions);
// - every tracked-surface face it creates or moves stays inside the envelope,
//   keeps the input-triangle ids of the face(s) it came from, and the
//   tracked surface keeps its topology (collapses pass a link condition on
//   the tet mesh and on the tracked surface; swaps never cross tracked faces);
// - kLocked and kOnBoundary vertices never move; hull (box) vertices only
//   slide within their box face(s) and are never collapsed away.
// Operations are applied in a fixed order and the parallel parts work on
// independent sets, so the result does not depend on the thread count.

#include <mr/core/scalar_field.h>
#include <mr/core/triangle_soup.h>
#include <mr/envelope/envelope.h>
#include <mr/tetmesh/logger.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/stats.h>

#include <cstddef>
#include <vector>

namespace mr::tetmesh {

struct ImproveOptions {
  /// Target edge length, absolute (> 0). Edges longer than 4/3 of the local
  /// target are split, shorter than 4/5 collapsed.
  double target_edge_length = 0.0;
  /// Improvement stops once the largest AMIPS energy is below this.
  double stop_energy = 10.0;
  /// Upper bound on the number of passes (split, collapse, swap, smooth).
  int max_passes = 80;
  /// Worker threads; 0 means all hardware threads. The output is the same
  /// for every value.
  int threads = 0;
  /// After a pass that lowered the energies little, the local target length
  /// shrinks around the tets of high energy and grows back elsewhere (the
  /// paper's adaptive refinement), never below this fraction of the target
  /// at first. Once the target reached this floor and five more passes
  /// lowered the largest energy by less than 1%, the floor halves (at most
  /// floor_halvings times) if the bad tets are few, or improvement ends; it ends at
  /// the stop energy or after max_passes too. A deep floor from the first
  /// pass was measured worse: at epsilon (fTetWild's), splits and collapses
  /// traded places for dozens of passes (thingi10k/61460: 900k splits, max
  /// AMIPS stuck at 33).
  double min_sizing = 0.25;
  /// How many times the floor may halve (see min_sizing). A fourth and
  /// fifth halving made trimesh/angle_block worse (max AMIPS 18.6 -> 35.8,
  /// 54k -> 326k tets); a stage that ends worse than the one before it is
  /// undone, so more halvings cost time, not quality.
  int floor_halvings = 3;
  /// With SurfaceBounds::triangles, creased vertices where parts meet or
  /// cross (or copies overlap) may move where their tets are bad too, not
  /// only those of one sheet. Projected onto one part's triangle, such a
  /// vertex can turn the other part's faces over for a filter that orients
  /// tracked faces by geometry afterwards (openscad-nonmanifold-crash left
  /// the envelope by 19 eps): only for a filter that reads its decision
  /// from before (TetPayload::value), as the pipeline does when the
  /// tracked surface is a cycle or the input is open, or that decides per
  /// tet and keeps only tets improved as kWritten.
  bool release_junctions = false;
  /// A target edge length that varies in space (absolute, not owned; null:
  /// target_edge_length everywhere). Sampled at each vertex where it is made
  /// and clamped to [1/100, 100] times target_edge_length; where it is NaN,
  /// target_edge_length holds. Improvement then also goes on, past the stop
  /// energy, while a pass changes the number of tets by more than 2%.
  const ScalarField* sizing = nullptr;
};

/// Quality of the live tets, measured on the double (approx) positions.
struct QualitySummary {
  std::size_t tets = 0;
  double min_dihedral_deg = 0.0;      ///< smallest dihedral angle of all tets
  double avg_min_dihedral_deg = 0.0;  ///< mean over tets of their smallest angle
  double max_amips = 0.0;             ///< 3 for a regular tet
  double avg_amips = 0.0;
};

struct ImproveStats {
  std::size_t splits = 0;
  std::size_t collapses = 0;
  std::size_t swaps_32 = 0;
  std::size_t swaps_23 = 0;
  std::size_t swaps_44 = 0;
  std::size_t edge_removals = 0;  ///< edges in 5 to 7 tets removed
  std::size_t smoothing_moves = 0;
  std::size_t refinements = 0;  ///< times a vertex's local target shrank
  /// With a sizing field, of the vertices at the start: where it gave no
  /// value (the global target held), and where its value was clamped.
  std::size_t sizing_outside = 0;
  std::size_t sizing_clamped = 0;
  int passes = 0;
  /// Times the floor of the local target (ImproveOptions::min_sizing)
  /// halved, and whether the last of those stages ended worse than the one
  /// before it and was undone (1) or not (0).
  int floor_halvings = 0;
  int floor_stages_undone = 0;
  /// Passes without splits after the others ended above the stop energy;
  /// the mesh ends as the best of them (or as the passes left it).
  int polish_passes = 0;
  /// The largest energy over the kWritten tets when the passes with splits ended.
  double passes_max_amips = 0.0;
  QualitySummary before;
  QualitySummary after;
  /// The largest energy at the end over the kWritten tets (all tets when
  /// no fates were given, TetPayload).
  double written_max_amips = 0.0;
  std::size_t rational_vertices = 0;  ///< live vertices still rational at the end
  /// The kWritten tets left at or above the stop energy, and what holds them.
  StuckReport stuck;
};

struct RoundingStats {
  std::size_t rational_before = 0;
  std::size_t rounded = 0;    ///< rounded in place (try_round)
  std::size_t moved = 0;      ///< moved to a nearby double position
  std::size_t collapsed = 0;  ///< collapsed onto a neighbour with double coordinates
  std::size_t remaining = 0;  ///< still rational
};

/// What the tracked surface must stay near (the envelopes are not owned).
struct SurfaceBounds {
  SurfaceBounds(const envelope::Envelope& surface_,
                const envelope::Envelope* open_boundary_ = nullptr)  // NOLINT
      : surface(surface_), open_boundary(open_boundary_) {}
  /// Every tracked face stays inside.
  const envelope::Envelope& surface;
  /// The envelope of the input's open boundary edges (seed section 3.4,
  /// "Open Boundaries"), null when it has none: a tracked edge with one
  /// face stays inside it, so that a boundary cannot drift across the
  /// surface while its faces stay in the surface envelope.
  const envelope::Envelope* open_boundary;
  /// The triangles the tracked faces' ids name, or null. With them, a
  /// vertex on a crease of one sheet (of any, with
  /// ImproveOptions::release_junctions) may move where its tets are bad:
  /// it is projected back onto the nearest of its own triangles.
  const TriangleSoup* triangles = nullptr;
};

/// Improves `mesh` in place. Precondition: find_mesh_inconsistency(mesh) == ""
/// and every tracked face inside `bounds.surface`. Throws mr::UsageError on a
/// non-positive target edge length or stop energy.
ImproveStats improve_mesh(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                          const Logger& logger = {});
/// What the filter (stage 6) will do with a tet, foreseen for improvement.
enum TetFate : char {
  kWritten = 0,        ///< kept: its energy drives the passes and the stop
  kBesideWritten = 1,  ///< removed, with a corner on a kept tet: its energy
                       ///< blocks operations that would raise it, no more
  kDropped = 2,        ///< removed: only its positivity is kept
};

/// What improvement carries from the tets it replaces to the tets it makes,
/// one entry per tet slot in each vector (or none: empty).
/// - `fate`: the passes work on the kWritten tets, and the stop energy is
///   measured there. Every tet stays strictly positive and the tracked
///   surface in the envelope whatever its fate.
/// - `value`: the filter's winding number per tet, its decision (kept by
///   |w| > 1/2 or w > 1/2), carried through improvement so that the filter
///   reads it afterwards. Tracked faces where the decision changes keep
///   their topology; the others (crossings inside the solid, flaps outside
///   it) only stay in the envelope, and may be pinched onto another sheet.
/// A new tet takes the entries of the tet it was made from (a split's half,
/// a collapse's moved tet); a swap's new tets take the value of the first
/// old tet (swaps never merge tets of different decisions) and the mildest
/// fate. On return both have one entry per slot of the improved mesh
/// (those of removed slots mean nothing).
struct TetPayload {
  std::vector<char> fate;
  std::vector<double> value;
};

/// The same, carrying `payload` along. Throws mr::UsageError when a
/// non-empty vector of it has the wrong size.
ImproveStats improve_mesh(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                          TetPayload& payload, const Logger& logger = {});

/// Rounds every rational vertex to doubles where no incident tet inverts; a
/// vertex that cannot be rounded in place is moved to a nearby double
/// position or collapsed onto a neighbour (same checks as improve_mesh),
/// then retried. `remaining` says how many are left rational.
RoundingStats round_vertices(Mesh& mesh, const SurfaceBounds& bounds, const Logger& logger = {});

/// Quality of the live tets (parallel, deterministic).
QualitySummary measure_quality(const Mesh& mesh);

/// Splits edge (a, b) at `position` (any point, rational or not, for which
/// every new tet is strictly positive): each tet around the edge becomes
/// two. Tracked faces on the edge keep their ids on both halves; the new
/// vertex gets kOnSurface / kOnBox as the edge. No envelope test here.
/// Returns the new vertex, or kNoVertex (mesh untouched) when (a, b) is not
/// an edge or a new tet would not be strictly positive.
Index split_edge(Mesh& mesh, Index a, Index b, const HybridPoint& position);

}  // namespace mr::tetmesh
