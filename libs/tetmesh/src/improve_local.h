#pragma once
// Shared machinery of the mesh-improvement operations (improve_*.cpp): the
// workspace (mesh, envelope, a seed tet per vertex to find stars, the local
// sizing), star queries, the exact and envelope checks every operation runs
// before it edits anything, and the one routine that replaces a cavity of
// tets while carrying the tracked-surface ids over.

#include <mr/core/scalar_field.h>
#include <mr/envelope/envelope.h>
#include <mr/tetmesh/improve.h>
#include <mr/tetmesh/mesh.h>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace mr::tetmesh::improve_detail {

using FaceKey = std::array<Index, 3>;  ///< sorted corners of a face
FaceKey face_key(std::array<Index, 3> corners);

/// A face replaced or moved by an operation: its corners (any order).
using FaceCorners = std::array<Index, 3>;

/// Stands for the not-yet-created vertex of a split in the checks below.
inline constexpr Index kNewVertex = kNoVertex - 1;

class Workspace {
 public:
  /// `envelope` may be null: no tracked face may then move or change.
  Workspace(Mesh& mesh, const envelope::Envelope* envelope, double target_edge_length, double stop_energy);

  Mesh& mesh;
  const envelope::Envelope* envelope;
  /// The input's open boundary edges (SurfaceBounds), or null.
  const envelope::Envelope* open_boundary = nullptr;
  /// The triangles the tracked ids name (SurfaceBounds), or null.
  const TriangleSoup* triangles = nullptr;
  double target_edge_length;
  double stop_energy;
  /// Per vertex slot: scale of the local target length (1: the global
  /// target), shrunk around bad tets by update_sizing.
  std::vector<double> sizing;
  /// Per vertex slot: the user's sizing field at the vertex over the global
  /// target (1 without a field), sampled where the vertex was made.
  std::vector<double> field_scale;
  /// ImproveOptions::release_junctions.
  bool release_junctions = false;
  /// Edges shorter than this share of their target are collapsed (longer
  /// than 4/3 of it split). 4/5 as fTetWild by default; with a sizing field
  /// 2/3, so that the halves of a split edge are never collapse candidates
  /// (with 4/5, splits and collapses of edges between 4/3 and 8/5 of their
  /// target undid each other on 40% of the tets every pass, trimesh/teapot).
  double collapse_below = 0.8;
  /// Per tet slot, its fate and value (TetPayload, improve.h); kept up to
  /// date by replace_tets.
  TetPayload payload;

  /// Per vertex slot, whether the pass works there; empty: everywhere.
  /// Once few tets are bad, passes work only around them (improve_driver.cpp).
  std::vector<char> focus;
  bool in_focus(Index v) const { return focus.empty() || (v < focus.size() && focus[v] != 0); }

  /// Whether tet t's energy may block an operation (kWritten, kBesideWritten).
  bool counts(Index t) const { return t >= payload.fate.size() || payload.fate[t] != kDropped; }
  /// Whether tet t's energy drives the passes and the stop (kWritten).
  bool drives(Index t) const { return t >= payload.fate.size() || payload.fate[t] == kWritten; }
  /// The tets of `tets` whose energy counts.
  std::vector<Index> counted(std::span<const Index> tets) const;
  /// Whether the filter's carried decision (TetPayload::value) keeps tet t,
  /// by either winding rule (|w| > 1/2, w > 1/2); {false, false} for
  /// kNoTet, whose space the hull removes. Only with a carried decision.
  std::pair<bool, bool> kept_side(Index t) const;
  /// Whether `tets` carry different decisions (TetPayload::value): an
  /// operation that merges them would move the written mesh's boundary.
  bool mixes_decisions(std::span<const Index> tets) const;

  /// The live tets around v, sorted. Empty for a vertex no tet uses.
  std::vector<Index> star(Index v);
  /// The same without refreshing a stale seed (safe beside other readers):
  /// nullopt when v's seed no longer holds it.
  std::optional<std::vector<Index>> seeded_star(Index v) const;
  /// The tets containing edge (a, b), sorted; empty if it is not an edge.
  /// `hint`, when it is a live tet with both corners, saves the walk around
  /// a's star to find one (long on the cut points where many triangles cross).
  std::vector<Index> edge_tets(Index a, Index b, Index hint = kNoTet);
  /// How the sizing field answered at the vertices sampled.
  struct FieldSamples {
    std::size_t outside = 0;  ///< no value: the global target holds
    std::size_t clamped = 0;  ///< beyond [1/100, 100] times the global target
  };
  /// Samples `field` (ImproveOptions::sizing) at every live vertex, and
  /// from now on at every vertex made.
  FieldSamples use_sizing_field(const ScalarField* field);
  bool has_sizing_field() const { return field_ != nullptr; }
  /// Local target length at vertex v over the global one: the sizing
  /// field's scale times the refinement's.
  double scale(Index v) const;
  /// Target length of edge (a, b): the mean of its ends' local targets.
  double target(Index a, Index b) const;
  /// Records that `tets` are live and use their corners (after an edit).
  void note_tets(std::span<const Index> tets);
  /// Records new vertex v with refinement scale `size`; samples the field.
  void note_vertex(Index v, double size);
  /// Finds a tet for every vertex again (after the mesh was replaced as a whole).
  void reset_seeds();

 private:
  Index find_seed(Index v);
  enum class Sample : char { inside, outside, clamped };
  std::pair<double, Sample> sampled_scale(Index v) const;
  const ScalarField* field_ = nullptr;
  std::vector<Index> seed_;
};

/// Position of corner v, with vertex `moved` (or kNewVertex) replaced by `at`.
struct Override {
  Index vertex = kNoVertex;
  const HybridPoint* at = nullptr;
};

/// Every tet strictly positive, exactly, on the hybrid positions.
bool all_positive(const Mesh& mesh, std::span<const Tet> tets, Override moved = {});
/// AMIPS energies on the double positions (+inf for flat or inverted).
double max_energy(const Mesh& mesh, std::span<const Tet> tets, Override moved = {});
double max_energy_of(const Mesh& mesh, std::span<const Index> tets);
double tet_energy(const Mesh& mesh, Index t);
/// Every face inside the envelope (true when there are none; false when
/// there are some and no envelope).
bool faces_inside(const Workspace& ws, std::span<const FaceCorners> faces, Override moved = {});

/// Tracked faces (as sorted keys with their ids) of a set of tets, each once.
struct TrackedFace {
  FaceKey key;
  std::vector<std::uint32_t> ids;
};
std::vector<TrackedFace> tracked_faces(const Mesh& mesh, std::span<const Index> tets);
/// The tracked faces among them that contain vertex v.
std::vector<TrackedFace> tracked_faces_at(const Mesh& mesh, std::span<const Index> star, Index v);

/// For a face of a new tet, the faces of the old tets it came from (their
/// ids are united onto it); leave empty for a face that is new.
using ParentFaces = std::function<void(const FaceKey& face, std::vector<FaceKey>& parents)>;

/// Removes `old_tets`, adds `new_tets`, re-links them with the tets around
/// the cavity and gives each new face the ids of its parents. The caller has
/// checked that the new tets fill the cavity and are positive. A new tet
/// takes the payload (Workspace::payload) of its origin (`origin[i]`, an
/// index into old_tets); without origins, the mildest fate of the old tets
/// and the value of the first. Returns the new tets.
std::vector<Index> replace_tets(Workspace& ws, std::span<const Index> old_tets, std::span<const Tet> new_tets,
                                const ParentFaces& parents, std::span<const std::size_t> origin = {});

/// True when a face of one of `tets` containing both a and b lies on the hull.
bool edge_on_hull(const Mesh& mesh, std::span<const Index> tets, Index a, Index b);
/// True when some face of `tets` containing v lies on the hull.
bool vertex_on_hull(const Mesh& mesh, std::span<const Index> tets, Index v);

// ---- operations (each in its own improve_*.cpp) ----

/// Splits edge (a, b) at `at` if allowed; returns the new vertex or kNoVertex.
/// `hint`: as for Workspace::edge_tets.
Index try_split(Workspace& ws, Index a, Index b, const HybridPoint& at, bool check_envelope,
                Index hint = kNoTet);
/// A split of edge (a, b) that passed every check: each of `old_tets` (the
/// tets around the edge) becomes two of `new_tets` (its origin), with the
/// new vertex, at `at` with `flags`, standing as kNewVertex.
struct SplitPlan {
  Index a = kNoVertex, b = kNoVertex;
  HybridPoint at;
  std::vector<Index> old_tets;
  std::vector<Tet> new_tets;
  std::vector<std::size_t> origin;
  std::uint8_t flags = 0;
};
/// The checks of try_split on the tets around the edge; changes nothing
/// (several threads may plan at once).
std::optional<SplitPlan> plan_split(const Workspace& ws, Index a, Index b, const HybridPoint& at,
                                    bool check_envelope, std::vector<Index> old_tets);
/// Returns the new vertex.
Index apply_split(Workspace& ws, SplitPlan plan);

enum class CollapseGoal { quality, rounding };
/// Collapses u onto v if every check passes.
bool try_collapse(Workspace& ws, Index u, Index v, CollapseGoal goal);
/// A collapse of u onto v that passed every check: u's star and the tets
/// that replace it (new_tets[i] is star_u[origin[i]] with u moved to v).
struct CollapsePlan {
  Index u = kNoVertex, v = kNoVertex;
  std::vector<Index> star_u;
  std::vector<Tet> new_tets;
  std::vector<std::size_t> origin;
};
/// The checks of try_collapse, changing nothing but the star seeds.
std::optional<CollapsePlan> plan_collapse(Workspace& ws, Index u, Index v, CollapseGoal goal);
void apply_collapse(Workspace& ws, const CollapsePlan& plan);
/// The collapse pass's decision on edge (a, b), a onto b else b onto a,
/// taken without changing anything (several threads may decide at once);
/// undecided when a seed is stale, so a star cannot be found read-only.
struct EdgeCollapse {
  enum class Kind { refused, planned, undecided } kind;
  CollapsePlan plan;
};
EdgeCollapse decide_edge_collapse(const Workspace& ws, Index a, Index b);

/// A swap that passed every check: `old_tets` become `new_tets`. `kind`: 2
/// for a 2-3 face removal, else the number of tets around the removed edge
/// (3: a 3-2 swap, 4: 4-4, 5 to 7: edge removal).
struct SwapPlan {
  std::vector<Index> old_tets;
  std::vector<Tet> new_tets;
  int kind = 0;
};
/// Edge removal of edge (a, b) of live tet `hint`: the n tets around it (3
/// to 7) become 2n - 4, if that lowers their largest energy. Changes nothing.
std::optional<SwapPlan> plan_edge_swap(const Workspace& ws, Index a, Index b, Index hint);
/// Face removal (2-3) of face `f` of live tet `t`. Changes nothing.
std::optional<SwapPlan> plan_face_swap(const Workspace& ws, Index t, int f);
/// The first swap of live tet t that passes: its edges in corner order,
/// then its faces. Changes nothing (several threads may plan at once).
std::optional<SwapPlan> plan_tet_swap(const Workspace& ws, Index t);
void apply_swap(Workspace& ws, const SwapPlan& plan);

/// Moves v to lower the AMIPS energy of its star (Newton with line search)
/// within its constraints. `star` are its tets. Touches only v's position.
/// With `soft_max`, a vertex of a tet at or above the stop energy lowers a
/// soft maximum of its star's energies instead of their sum.
bool try_smooth(const Workspace& ws, Index v, std::span<const Index> star, bool soft_max = false);
/// How freely try_smooth may move vertex v (`star`: its tets), freest first:
/// anywhere; within the tracked surface's tangent plane or its box face(s);
/// only where its tets are bad, back onto its input triangles (a crease or
/// an open boundary of one sheet, StuckReport::creased); not at all.
enum class Mobility : std::uint8_t { free, sliding, creased, fixed };
Mobility mobility(const Workspace& ws, Index v, std::span<const Index> star);
/// Moves a rational vertex to a nearby double position keeping its star
/// positive and its tracked faces in the envelope.
bool try_relocate(const Workspace& ws, Index v, std::span<const Index> star);
/// Drops the rational part of v when its nearest doubles keep the star positive.
bool try_round_in_place(Workspace& ws, Index v);

// ---- passes (improve_passes.cpp); each returns the number of operations done ----
std::size_t split_pass(Workspace& ws);
std::size_t collapse_pass(Workspace& ws);
struct SwapCounts {
  std::size_t s32 = 0, s23 = 0, s44 = 0, removals = 0;
};
SwapCounts swap_pass(Workspace& ws);
std::size_t smooth_pass(Workspace& ws, bool soft_max);
struct SizingUpdate {
  std::size_t shrunk = 0;  ///< vertices whose local target shrank
  bool hit_floor = false;  ///< some target would have gone below the floor
};
/// Shrinks the local target around the tets of high energy (relative to
/// `max_energy`; `energy` per tet slot, as tet_energies gives) and lets it
/// grow back elsewhere, within [min_scale, 1].
SizingUpdate update_sizing(Workspace& ws, std::span<const double> energy, double max_energy,
                           double min_scale);
/// The tets that drive (Workspace::drives) at or above the stop energy,
/// counted by the freest of their corners, and the `worst` worst of them.
/// `energy`: per tet slot, as tet_energies(ws, true) gives.
StuckReport stuck_report(Workspace& ws, std::span<const double> energy, std::size_t worst);
/// Energy of every live tet slot that counts, or with `driving_only` that
/// drives (0 for the others), in parallel.
std::vector<double> tet_energies(const Workspace& ws, bool driving_only = false);

}  // namespace mr::tetmesh::improve_detail
