#include <mr/tetmesh/tetrahedralize.h>

#include "filter_preview.h"
#include "filter_stage.h"
#include "part_labels.h"
#include "regions.h"
#include "rounding_stage.h"
#include "sheet_solids.h"

#include <mr/core/double_sided.h>
#include <mr/core/errors.h>
#include <mr/core/grid_snap.h>
#include <mr/core/orientation.h>
#include <mr/core/weld.h>
#include <mr/envelope/envelope.h>
#include <mr/simplify/simplify.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/spatial/defect_faces.h>
#include <mr/tetmesh/background_mesh.h>
#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/improve.h>
#include <mr/tetmesh/insertion.h>
#include <mr/tetmesh/winding_filter.h>

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace mr::tetmesh {
namespace {

// The paper simplifies with a smaller envelope than the one the mesh must
// respect, leaving room for the later stages (fTetWild: 0.8 epsilon).
constexpr double kSimplifyEpsilonFraction = 0.8;
// Improvement samples the envelope this much finer (see improvement_envelope).
constexpr double kImprovementSamplingRefinement = 8.0;

struct Simplified {
  TriangleSoup surface;
  /// simplify_near_defects_only found every face near a defect: none was
  /// kept out of the simplification.
  bool every_face_near_defects = false;
};

Simplified simplified_input(const TriangleSoup& input, const PipelineOptions& options,
                            const DerivedParameters& derived, PipelineStats& stats, const Logger& logger) {
  StageTimer timer(stats, "simplify", logger);
  if (options.tetrahedralize.skip_simplify) {
    timer.stage().count("faces", static_cast<std::int64_t>(input.triangles.size()));
    return {input, false};
  }
  simplify::SimplifyOptions simplify_options;
  simplify_options.epsilon_abs = kSimplifyEpsilonFraction * derived.epsilon;
  simplify_options.threads = options.tetrahedralize.threads;
  bool every_face_near_defects = false;
  if (options.tetrahedralize.simplify_near_defects_only) {
    std::vector<std::uint8_t> near =
        spatial::faces_near_defects(input, options.tetrahedralize.defect_band_rings);
    const auto near_count = static_cast<std::size_t>(std::count(near.begin(), near.end(), 1));
    timer.count("faces_near_defects", near_count);
    if (near_count == 0) {
      timer.stage().count("faces", static_cast<std::int64_t>(input.triangles.size()));
      return {input, false};
    }
    every_face_near_defects = near_count == near.size();
    for (std::uint8_t& f : near) f = !f;
    simplify_options.frozen_faces = std::move(near);
  }
  simplify::SimplifyResult result = simplify::simplify_in_envelope(input, simplify_options);
  timer.stage().count("faces_before", static_cast<std::int64_t>(result.faces_before));
  timer.stage().count("faces", static_cast<std::int64_t>(result.faces_after));
  return {std::move(result.soup), every_face_near_defects};
}

// The insertion budget (max_insertion_tets) bounds what keeping the faces
// away from defects unsimplified costs. Where every face was simplified
// (no face kept, or every face near a defect), the insertion is the one a
// full rebuild would run: max_rebuild_insertion_tets bounds it instead.
bool rebuilds_every_face(const PipelineOptions& options, const Simplified& simplified) {
  return !options.tetrahedralize.simplify_near_defects_only || simplified.every_face_near_defects;
}

PipelineOptions budget_applied(const PipelineOptions& options, const Simplified& simplified) {
  PipelineOptions applied = options;
  if (rebuilds_every_face(options, simplified))
    applied.tetrahedralize.max_insertion_tets = options.tetrahedralize.max_rebuild_insertion_tets;
  return applied;
}

// Embeddings to try before giving up: when some cut points cannot be
// rounded even after improvement, the embedding starts over from a fresh
// background mesh (see embed_and_improve).
constexpr int kEmbeddingAttempts = 8;

std::unique_ptr<envelope::Envelope> input_envelope(const TriangleSoup& input,
                                                   const DerivedParameters& derived) {
  envelope::EnvelopeOptions envelope_options;
  envelope_options.epsilon = derived.epsilon;
  return envelope::make_envelope(input, envelope_options);
}

// The envelope improvement checks moved faces against. The simplified
// surface may lie up to kSimplifyEpsilonFraction * epsilon from the input;
// sampled at step epsilon, the test asks every sample to be within
// (1 - 1/sqrt(3)) epsilon = 0.42 epsilon, so no face on a simplified
// triangle could be moved or replaced wherever the simplifier had used its
// room, and the tets on it stayed as bad as insertion left them (c3d/beetle's
// worst tet: an edge 3e-6 long that no collapse could remove). At step epsilon / 8 the samples need
// 0.93 epsilon; the adaptive pattern bisects only pieces near the limit.
std::unique_ptr<envelope::Envelope> improvement_envelope(const TriangleSoup& input,
                                                         const DerivedParameters& derived) {
  envelope::EnvelopeOptions envelope_options;
  envelope_options.epsilon = derived.epsilon;
  envelope_options.sampling_step = derived.epsilon / kImprovementSamplingRefinement;
  envelope_options.pattern = envelope::SamplingPattern::Adaptive;
  return envelope::make_envelope(input, envelope_options);
}

// The envelope of the input's open boundary: its edges used by one triangle
// (vertices welded when bit-identical), each as a degenerate triangle, whose
// distance is the distance to the segment. Null when the input is closed.
std::unique_ptr<envelope::Envelope> open_boundary_envelope(const TriangleSoup& input,
                                                           const DerivedParameters& derived) {
  const TriangleSoup welded = weld_identical_vertices(input);
  std::vector<std::array<Index, 2>> edges;
  for (const Triangle& t : welded.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    for (int i = 0; i < 3; ++i)
      edges.push_back({std::min(t[i], t[(i + 1) % 3]), std::max(t[i], t[(i + 1) % 3])});
  }
  std::sort(edges.begin(), edges.end());
  TriangleSoup boundary;
  boundary.positions = welded.positions;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary.triangles.push_back({edges[i][0], edges[i][1], edges[i][1]});
    i = j;
  }
  if (boundary.triangles.empty()) return nullptr;
  return input_envelope(boundary, derived);
}

std::size_t count_rational(const Mesh& mesh) {
  std::size_t count = 0;
  for (Index v = 0; v < mesh.vertex_slots(); ++v)
    count += mesh.vertex_alive(v) && mesh.position(v).is_exact();
  return count;
}

struct Embedding {
  Mesh mesh;
  /// Per vertex slot, the input triangle (or polygon, by its first
  /// triangle) whose insertion created it.
  std::vector<std::uint32_t> creator;
  /// Per input triangle, the polygon it was inserted in (InsertionStats::marked_as).
  std::vector<std::uint32_t> marked_as;
};

// Background mesh, insertion of every triangle not skipped, and rounding of
// the cut points as far as local moves inside the envelope allow.
Embedding embed_once(const TriangleSoup& surface, std::span<const char> skip, const SurfaceBounds& bounds,
                     const DerivedParameters& derived, const PipelineOptions& options, PipelineStats& stats,
                     const Logger& logger) {
  BackgroundMesh background;
  {
    StageTimer timer(stats, "background", logger);
    background = build_background_mesh(surface, spatial::AabbTree(surface),
                                       background_parameters(derived, options.tetrahedralize.threads));
    timer.count("vertices", background.mesh.num_vertices());
    timer.count("tets", background.mesh.num_tets());
  }
  Embedding embedding{std::move(background.mesh), {}, {}};
  Mesh& mesh = embedding.mesh;
  {
    StageTimer timer(stats, "insertion", logger);
    InsertionOptions insertion;
    insertion.max_tets = options.tetrahedralize.max_insertion_tets;
    // Snapping spares improvement knots it cannot untie; without
    // improvement (meshrepair) it only cost time: manifold/Offset1's kept
    // try 14 -> 61 s.
    insertion.snap_distance = options.improve ? derived.snap_spacing : 0.0;
    // Settling and the random order go together. Settled in input order,
    // the patches of a CAD model's overlapping coplanar parts were cut
    // along each other's lines again and again, and their exact points grew
    // past 100,000 bits (trimesh/chair_model's repair: over 300 s, against
    // 34 s unsettled); settled in random order, 12,000 bits at most and
    // 10 s. Unsettled, the random order alone made more cut points there
    // (76k -> 130k).
    insertion.random_order = true;
    insertion.settle_cut_points = true;
    InsertionStats inserted =
        insert_triangles(mesh, surface, background.input_vertex, skip, logger, insertion);
    timer.count("triangles", inserted.inserted);
    timer.count("degenerate_skipped", inserted.degenerate);
    timer.count("copies", inserted.copies);
    timer.count("coplanar_polygons", inserted.polygons);
    timer.count("merged_triangles", inserted.merged);
    timer.count("left_out", inserted.skipped);
    timer.count("cut_points", inserted.new_vertices);
    timer.count("steiner_points", inserted.steiner_points);
    timer.count("eagerly_rounded", inserted.eagerly_rounded);
    timer.count("already_faces", inserted.already_faces);
    timer.count("snapped_points", inserted.snapped_points);
    timer.count("settled_points", inserted.settled_points);
    timer.count("tets", mesh.num_tets());
    embedding.creator = std::move(inserted.vertex_creator);
    embedding.marked_as = std::move(inserted.marked_as);
  }
  StageTimer timer(stats, "rounding", logger);
  // A cut point closer than this to a neighbour may be merged with it: far
  // below epsilon, so the tracked surface stays in the envelope.
  const detail::RoundingCounters rounding = detail::round_or_collapse(mesh, 1e-3 * derived.epsilon);
  timer.count("rounded", rounding.rounded);
  timer.count("collapsed", rounding.collapsed);
  std::size_t remaining = rounding.remaining;
  if (remaining != 0) {
    // Moves within the envelope: to nearby doubles, or onto any neighbour.
    const RoundingStats moved = round_vertices(mesh, bounds, logger);
    timer.count("moved", moved.moved + moved.collapsed);
    remaining = moved.remaining;
  }
  timer.count("rational_vertices", remaining);
  return embedding;
}

// An open input's per-tet decision is carried through improvement only
// when it changes mostly on tracked faces. Swaps never merge tets of
// different decisions, so where it changes across open space they are
// blocked: on trimesh/soup (100 crossing triangles, 24% of its deciding
// faces untracked) max AMIPS went from 63 to 2,308 carried.
constexpr double kMaxUntrackedShare = 0.2;

// Whether improvement carries the filter's decision: decided by region, or
// per tet on an open input where it changes mostly on tracked faces. (A
// closed input whose tracked surface is no cycle is decided after
// improvement, around its left-out triangles or per tet within the
// envelope: openscad-nonmanifold-crash, closed but not manifold.)
bool carries_decision(const Mesh& mesh, const detail::FilterPreview& preview, bool open_input,
                      StageTimer& timer) {
  if (preview.by_region || !open_input) return preview.by_region;
  const detail::DecisionFaces faces = detail::decision_faces(mesh, preview.winding);
  timer.count("deciding_faces_tracked", faces.tracked);
  timer.count("deciding_faces_untracked", faces.untracked);
  return faces.untracked_share() <= kMaxUntrackedShare;
}

// Improvement, on the tets that will be written when the filter runs
// (TetFate, improve.h). Returns what it carried for the filter: the winding
// number per tet slot, decided before improvement, and the fates it worked
// with. It is carried
// - when the filter was decided by region (the tracked surface's
//   orientation is guessed from geometry, and faces that improvement moved
//   and flattened made a closed input's tracked surface open:
//   trimesh/counter.unitsmm, 3 to 6 edges, so the filter fell back to
//   per-tet numbers and its boundary left the envelope where it had opened);
// - on an open input, decided per tet. Asked again after improvement, the
//   numbers of a moved surface could keep tets improvement had left alone
//   as removed, and every tracked face had to keep its topology, so that
//   lines where parts cross inside the solid held slivers (trimesh/suzanne
//   16.9, CesiumMilkTruck 14.2, derived/ogre 17.4 max AMIPS; 9.9, 10.0 and
//   10.0 carried), where its decision changes mostly on tracked faces.
// Vertices where parts meet or cross may move where moving them cannot
// mislead the filter: when it reads the carried numbers, or where it
// decides per tet and keeps only tets improved as written (filter_stage.h).
detail::CarriedDecision improve(Mesh& mesh, const SurfaceBounds& bounds, std::span<const char> left_out,
                                const DerivedParameters& derived, int max_passes,
                                const PipelineOptions& options, PipelineStats& stats, const Logger& logger) {
  StageTimer timer(stats, "improve", logger);
  ImproveOptions improve_options;
  improve_options.target_edge_length = derived.edge_length;
  improve_options.stop_energy = options.tetrahedralize.stop_energy;
  improve_options.max_passes = max_passes;
  improve_options.threads = options.tetrahedralize.threads;
  improve_options.sizing = options.sizing.get();
  TetPayload payload;
  bool by_region = false;
  if (options.filter && bounds.triangles != nullptr) {
    detail::FilterPreview preview = detail::preview_filter(mesh, *bounds.triangles, left_out);
    by_region = preview.by_region;
    const bool open_input = bounds.open_boundary != nullptr;
    const bool carried = carries_decision(mesh, preview, open_input, timer);
    if (!options.keep_rejected) payload.fate = detail::fates_from_winding(mesh, preview.winding, carried);
    if (carried) payload.value = std::move(preview.winding);
    // Not carried on an open input, the filter keeps only tets improved as
    // kWritten. (A closed input whose tracked surface is no cycle left the
    // envelope by 1.4 eps with released junctions: openscad-nonmanifold-crash.)
    improve_options.release_junctions = carried || (open_input && !payload.fate.empty());
    timer.count("junctions_released", improve_options.release_junctions ? 1 : 0);
    timer.count("dropped_tets", std::size_t(std::count(payload.fate.begin(), payload.fate.end(), kDropped)));
  }
  const ImproveStats improved = improve_mesh(mesh, bounds, improve_options, payload, logger);
  timer.count("passes", static_cast<std::size_t>(improved.passes));
  timer.count("polish_passes", static_cast<std::size_t>(improved.polish_passes));
  timer.count("floor_halvings", static_cast<std::size_t>(improved.floor_halvings));
  timer.count("floor_stages_undone", static_cast<std::size_t>(improved.floor_stages_undone));
  timer.count("splits", improved.splits);
  timer.count("collapses", improved.collapses);
  timer.count("swaps", improved.swaps_32 + improved.swaps_23 + improved.swaps_44 + improved.edge_removals);
  timer.count("smoothing_moves", improved.smoothing_moves);
  stats.stuck = improved.stuck;
  if (options.sizing != nullptr) {
    timer.count("sizing_field_outside", improved.sizing_outside);
    timer.count("sizing_field_clamped", improved.sizing_clamped);
  }
  timer.count("rational_vertices", improved.rational_vertices);
  if (improved.rational_vertices != 0) {
    // Its collapses make tets that carry nothing.
    const RoundingStats rounded = round_vertices(mesh, bounds, logger);
    timer.count("rational_vertices_after_rounding", rounded.remaining);
    return {};
  }
  return {std::move(payload.value), std::move(payload.fate), by_region};
}

// The surface on a grid of `spacing` (0: as it is).
TriangleSoup snapped_surface(const TriangleSoup& surface, double spacing, PipelineStats& stats,
                             const Logger& logger) {
  StageTimer timer(stats, "snap", logger);
  TriangleSoup snapped = surface;
  if (spacing > 0) {
    timer.stage().count("grid_log2", std::ilogb(spacing));
    timer.count("moved_vertices", snap_to_grid(snapped, spacing));
  }
  return snapped;
}

// A retry after cut points got stuck snaps the surface to a grid this much
// coarser, while the grid stays below kMaxRetrySnapFraction of epsilon (one
// step from the default); only then are triangles left out.
constexpr double kSnapCoarsening = 16.0;
constexpr double kMaxRetrySnapFraction = 1.0 / 32.0;

// Marks as left out the triangles (whole polygons) whose cut points are
// still rational; returns how many were not marked before. Rational points
// are only ever made by insertion, so a rational vertex still sits in the
// slot its creator gave it.
std::size_t leave_out_stuck_creators(const Embedding& embedding, std::vector<char>& left_out) {
  const Mesh& mesh = embedding.mesh;
  std::vector<char> stuck_creator(left_out.size(), 0);
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (!mesh.vertex_alive(v) || !mesh.position(v).is_exact() || v >= embedding.creator.size()) continue;
    const std::uint32_t creator = embedding.creator[v];
    if (creator != InsertionStats::kNoCreator) stuck_creator[creator] = 1;
  }
  std::size_t newly_left_out = 0;
  for (std::size_t i = 0; i < left_out.size(); ++i) {
    if (left_out[i] == 0 && stuck_creator[embedding.marked_as[i]] != 0) {
      left_out[i] = 1;
      ++newly_left_out;
    }
  }
  return newly_left_out;
}

struct EmbeddedSurface {
  Mesh mesh;
  /// The surface as embedded (snapped); its triangles are the input's.
  TriangleSoup surface;
  double snap_spacing = 0.0;
  /// Per triangle of `surface`, whether it had to be left out.
  std::vector<char> left_out;
  /// What improvement carried to the filter (see improve); empty without it.
  detail::CarriedDecision carried;
};

// Snaps and embeds the surface, improves the mesh when asked (checking
// moved faces against `improvement_surface`, non-null then), and makes
// sure every vertex has double coordinates. Cut points that rounding cannot
// place stay rational through improvement, which may free them by moving
// their neighbours. When some are still stuck the embedding is redone: on
// a coarser grid first, then without the triangles that created them. The
// fast path (no improvement) redoes it at once: two improvement passes to
// free the points cost more than a new embedding on a fragmented mesh
// (trimesh/featuretype: 100 s against 20 s).
EmbeddedSurface embed_and_improve(const TriangleSoup& simplified, const SurfaceBounds& bounds,
                                  const envelope::Envelope* improvement_surface,
                                  const DerivedParameters& derived, const PipelineOptions& options,
                                  PipelineStats& stats, const Logger& logger) {
  double spacing = derived.snap_spacing;
  EmbeddedSurface out{Mesh(),
                      snapped_surface(simplified, spacing, stats, logger),
                      spacing,
                      std::vector<char>(simplified.triangles.size(), 0),
                      {}};
  for (int attempt = 1;; ++attempt) {
    Embedding embedding = embed_once(out.surface, out.left_out, bounds, derived, options, stats, logger);
    Mesh& mesh = embedding.mesh;
    if (options.improve) {
      SurfaceBounds improving(*improvement_surface, bounds.open_boundary);
      improving.triangles = &out.surface;
      out.carried = improve(mesh, improving, out.left_out, derived, options.tetrahedralize.max_passes,
                            options, stats, logger);
    }
    const std::size_t remaining = count_rational(mesh);
    if (remaining == 0) {
      out.mesh = std::move(mesh);
      return out;
    }
    const bool coarsen = spacing > 0 && kSnapCoarsening * spacing <= kMaxRetrySnapFraction * derived.epsilon;
    const std::size_t newly_left_out = coarsen ? 0 : leave_out_stuck_creators(embedding, out.left_out);
    if (attempt == kEmbeddingAttempts || (!coarsen && newly_left_out == 0)) {
      throw RunError(std::to_string(remaining) +
                     " cut points could not be rounded to doubles "
                     "without inverting a tet; the mesh is not written");
    }
    const std::string stuck =
        std::to_string(remaining) + " cut points could not be rounded: inserting again ";
    if (coarsen) {
      spacing *= kSnapCoarsening;
      logger.log(LogLevel::warning,
                 stuck + "with the surface snapped to a grid of 2^" + std::to_string(std::ilogb(spacing)));
      out.surface = snapped_surface(simplified, spacing, stats, logger);
      out.snap_spacing = spacing;
    } else {
      logger.log(LogLevel::warning,
                 stuck + "without the " + std::to_string(newly_left_out) + " triangles that made them");
    }
  }
}

// Faces flipped against their neighbours would make the winding number dip
// inside the solid; orienting patches coherently first keeps the filter sound.
// A surface written double-sided (each face in both orientations) has
// winding number 0 everywhere: it is made one-sided and outward first. A
// face stored twice the same way round would count twice and split the
// patches at its edges, so flipped faces beside it would stay flipped.
TriangleSoup oriented_input(const TriangleSoup& input, PipelineStats& stats, const Logger& logger) {
  StageTimer timer(stats, "orient", logger);
  TriangleSoup oriented = input;
  timer.count("repeated_faces_dropped", drop_repeated_faces(oriented));
  timer.count("double_sided_copies_dropped", make_double_sided_components_one_sided(oriented));
  const OrientationStats orientation = orient_coherently(oriented);
  timer.count("patches", orientation.patches);
  timer.count("flipped", orientation.flipped);
  timer.count("conflicts", orientation.conflicts);
  return oriented;
}

// Labels the tets extracted from `mesh` by `keep` (in slot order) by the
// input part each lies in, and names the labels.
void label_parts(TetMesh& out, const Mesh& mesh, std::span<const char> keep, const TriangleSoup& oriented,
                 const PipelineOptions& options, StageTimer& timer) {
  detail::PartLabels parts =
      detail::part_labels(mesh, keep, oriented, options.labels, options.tetrahedralize.winding_rule);
  out.tet_labels.clear();
  for (Index t = 0; t < mesh.tet_slots(); ++t)
    if (keep[t]) out.tet_labels.push_back(parts.labels[t]);
  out.tet_label_names = std::move(parts.names);
  std::vector<std::int32_t> distinct = out.tet_labels;
  std::sort(distinct.begin(), distinct.end());
  timer.count("labels", std::size_t(std::unique(distinct.begin(), distinct.end()) - distinct.begin()));
}

// `stats` carries the stages of an earlier run, if any: their times add up.
PipelineResult run(const TriangleSoup& input, const PipelineOptions& options, PipelineStats stats,
                   const Logger& logger) {
  PipelineResult result;
  result.stats = std::move(stats);
  result.parameters = derive_parameters(options.tetrahedralize, input);
  const DerivedParameters& derived = result.parameters;
  const TriangleSoup oriented = oriented_input(input, result.stats, logger);
  const Simplified simplified_result = simplified_input(oriented, options, derived, result.stats, logger);
  const TriangleSoup& simplified = simplified_result.surface;
  const PipelineOptions embedding_options = budget_applied(options, simplified_result);

  const std::unique_ptr<envelope::Envelope> envelope = input_envelope(input, derived);
  const std::unique_ptr<envelope::Envelope> open_boundary = open_boundary_envelope(input, derived);
  const std::unique_ptr<envelope::Envelope> improving =
      options.improve ? improvement_envelope(input, derived) : nullptr;
  EmbeddedSurface embedded = [&] {
    try {
      return embed_and_improve(simplified, {*envelope, open_boundary.get()}, improving.get(), derived,
                               embedding_options, result.stats, logger);
    } catch (const InsertionTooCostly& e) {
      if (rebuilds_every_face(options, simplified_result)) throw RebuildTooCostly(e.what());
      throw;
    }
  }();
  Mesh& mesh = embedded.mesh;
  const TriangleSoup& surface = embedded.surface;
  const std::vector<char>& left_out = embedded.left_out;

  std::vector<char> keep;
  {
    StageTimer timer(result.stats, "filter", logger);
    if (options.filter) {
      const WindingRule rule = options.tetrahedralize.winding_rule;
      const TetClassification classes = detail::filter_tets(mesh, surface, left_out, embedded.carried,
                                                            derived.epsilon, *envelope, rule, timer);
      keep = classes.keep;
      timer.count("kept_tets", classes.kept);
    }
  }
  {
    StageTimer timer(result.stats, "output", logger);
    if (options.filter && !options.keep_rejected) {
      result.mesh = extract_tets(mesh, keep);
      label_parts(result.mesh, mesh, keep, oriented, options, timer);
    } else {
      // Every tet, labelled 1 / 0 by the filter or by its region.
      std::vector<std::int32_t> labels;
      if (options.filter)
        labels.assign(keep.begin(), keep.end());
      else
        labels = detail::region_labels(mesh);
      result.mesh = to_tet_mesh(mesh);
      for (Index t = 0; t < mesh.tet_slots(); ++t) {
        if (mesh.tet_alive(t)) result.mesh.tet_labels.push_back(labels[t]);
      }
    }
    result.tracked_surface = detail::tracked_surface(mesh, keep, surface);
    result.inserted_surface = surface;
    result.snap_spacing = embedded.snap_spacing;
    const std::size_t bad = detail::count_non_positive_tets(result.mesh);
    if (bad != 0) {
      throw RunError(std::to_string(bad) +
                     " tets are not positively oriented on the written "
                     "coordinates (internal error); the mesh is not written");
    }
    timer.count("tets", result.mesh.tets.size());
    timer.count("vertices", result.mesh.positions.size());
  }
  return result;
}

PipelineResult run_to_solid(const TriangleSoup& input, const PipelineOptions& options, const Logger& logger) {
  PipelineResult result = run(input, options, {}, logger);
  if (!options.filter) return result;
  return detail::solid_where_nothing_kept(input, options, std::move(result), run, logger);
}

}  // namespace

PipelineResult tetrahedralize(const TriangleSoup& input, const PipelineOptions& options,
                              const Logger& logger) {
  const int threads =
      options.tetrahedralize.threads > 0 ? options.tetrahedralize.threads : tbb::info::default_concurrency();
  tbb::task_arena arena(threads);
  return arena.execute([&] { return run_to_solid(input, options, logger); });
}

}  // namespace mr::tetmesh
