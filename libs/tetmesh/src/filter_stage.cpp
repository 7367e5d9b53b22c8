#include "filter_stage.h"

#include "regions.h"

#include <mr/core/weld.h>
#include <mr/tetmesh/improve.h>

#include <algorithm>

namespace mr::tetmesh::detail {
namespace {

// Removes from `classes` the kept tets that improvement did not work on as
// written. Where the per-tet winding numbers are asked after improvement,
// which moved the tracked surface, a tet it left alone as removed may come
// out above 1/2 with the shape insertion gave it (thingi10k/69166, open,
// before its decision was carried: max AMIPS 1.4e4 when kept). Returns how
// many.
std::size_t drop_unimproved(TetClassification& classes, std::span<const char> fate) {
  std::size_t dropped = 0;
  for (std::size_t t = 0; t < fate.size(); ++t) {
    if (classes.keep[t] != 0 && fate[t] != kWritten) {
      classes.keep[t] = 0;
      --classes.kept;
      ++dropped;
    }
  }
  return dropped;
}

// The filter's decision per tet when improvement carried none. The winding
// number of the tracked surface as it is now (after rounding and improvement
// moved it within the envelope), not of the raw input: its jumps then lie
// exactly on tracked faces, so the kept tets end there. Filtering with the
// input kept big tets whose centroid fell between the two surfaces, and
// their far faces left the envelope.
// A closed tracked surface (as most inputs give) needs one query per
// region. So does a closed input whose tracked surface is open only where
// triangles were left out, asked of the input itself, with the tets around
// those triangles deciding each for itself. Otherwise the winding number
// varies inside a region: every tet gets its own (open_tracked_winding).
TetClassification classify_tracked(Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out,
                                   std::span<const char> fate, double epsilon,
                                   const envelope::Envelope& envelope, WindingRule rule, StageTimer& timer) {
  std::vector<FaceRef> origins;
  const TriangleSoup tracked = tracked_surface(mesh, {}, surface, Multiplicity::as_chain, &origins);
  const std::vector<std::array<Index, 2>> open_edges = unbalanced_edges(tracked);
  timer.count("closed_surface", open_edges.empty() ? 1 : 0);
  if (open_edges.empty()) {
    timer.count("closed_input", 0);
    return classify_regions(mesh, WindingNumberTree(tracked), rule);
  }

  TriangleSoup holes;
  holes.positions = surface.positions;
  for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
    if (left_out[i] != 0) holes.triangles.push_back(surface.triangles[i]);
  }
  const std::vector<double> offsets = tracked_surface_offsets(mesh, surface);
  // How far from a left-out triangle an edge at the rim of its hole can be:
  // the neighbours' tracked faces end on its edges, moved off them by no
  // more than the largest offset.
  const double hole_reach =
      kOffsetMargin * (offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end())) +
      1e-9 * epsilon;
  // The tracked surface must be open only at the holes, or regions would
  // leak into each other (thingi10k/1514499 loses tracked faces somewhere
  // with none left out: one region took in 282k tets whose own winding
  // number said inside).
  const bool input_is_cycle = is_cycle(weld_identical_vertices(surface));
  const std::size_t away = edges_away_from(tracked, open_edges, holes, hole_reach);
  const bool closed_input = input_is_cycle && away == 0;
  timer.count("closed_input", closed_input ? 1 : 0);
  timer.count("input_is_cycle", input_is_cycle ? 1 : 0);
  timer.count("open_edges", open_edges.size());
  timer.count("open_edges_away_from_holes", away);
  if (closed_input) {
    BarrierRefinementStats refined;
    TetClassification classes =
        classify_with_refined_barrier(mesh, holes, WindingNumberTree(surface), rule, envelope, {}, refined);
    timer.count("barrier_tets", refined.barrier_tets);
    timer.count("barrier_rounds", static_cast<std::size_t>(refined.rounds));
    timer.count("barrier_splits", refined.splits);
    timer.count("barrier_faces_outside", refined.faces_outside);
    return classes;
  }
  OpenSurfaceStats open;
  const std::vector<double> winding =
      open_tracked_winding(mesh, tracked, origins, open_edges.size(), surface, left_out, open);
  TetClassification classes = classify_by_winding(mesh, winding, rule);
  timer.count("by_crossings", open.by_crossings ? 1 : 0);
  timer.count("cap_triangles", open.crossings.cap_triangles);
  timer.count("direct_queries", open.crossings.direct_queries);
  timer.count("full_crossing_tests", open.crossings.full_crossing_tests);
  timer.count("near_surface_queries", open.near_queries);
  timer.count("unimproved_tets_dropped", drop_unimproved(classes, fate));
  return classes;
}

}  // namespace

TetClassification filter_tets(Mesh& mesh, const TriangleSoup& surface, std::span<const char> left_out,
                              const CarriedDecision& carried, double epsilon,
                              const envelope::Envelope& envelope, WindingRule rule, StageTimer& timer) {
  if (carried.winding.empty())
    return classify_tracked(mesh, surface, left_out, carried.fate, epsilon, envelope, rule, timer);
  timer.count(carried.by_region ? "carried_by_region" : "carried_per_tet", 1);
  return classify_by_winding(mesh, carried.winding, rule);
}

}  // namespace mr::tetmesh::detail
