#include <mr/simplify/simplify.h>

#include <mr/core/orientation.h>
#include <mr/core/weld.h>

#include "mesh_state.h"
#include "passes.h"

#include <mr/core/errors.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>

namespace mr::simplify {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

DerivedTolerances derive_tolerances(const TriangleSoup& input, const SimplifyOptions& options) {
  if (!(options.epsilon_abs >= 0.0) || !std::isfinite(options.epsilon_abs))
    throw UsageError("absolute epsilon must be finite and >= 0");
  if (options.epsilon_abs == 0.0 && !(options.epsilon_rel > 0.0 && std::isfinite(options.epsilon_rel)))
    throw UsageError("relative epsilon must be finite and > 0");
  if (!(options.max_normal_deviation_deg > 0.0 && options.max_normal_deviation_deg <= 180.0))
    throw UsageError("maximum normal deviation must be in (0, 180] degrees");
  if (options.threads < 0) throw UsageError("thread count must be >= 0");
  DerivedTolerances t;
  t.epsilon =
      options.epsilon_abs > 0.0 ? options.epsilon_abs : options.epsilon_rel * bounding_box_diagonal(input);
  t.cos_max_normal_deviation = std::cos(options.max_normal_deviation_deg * std::numbers::pi / 180.0);
  return t;
}

// Simplifies `surface` inside the envelope of `reference`. Its patches are
// oriented coherently first: the halfedge mesh takes faces in input order and
// adds one that disagrees with the faces already in reversed, standing for a
// reversed copy that no collapse may merge with its neighbours; where regions
// grown from opposite orientations meet, faces fit neither way and are kept
// aside, their vertices locked. A scan stitched from inconsistently oriented
// pieces was locked that way (docs/ARCHITECTURE.md, Simplification).
SimplifyResult run(const TriangleSoup& surface, const TriangleSoup& reference, const SimplifyOptions& options,
                   const DerivedTolerances& tolerances) {
  SimplifyResult result;
  result.faces_before = surface.triangles.size();
  result.epsilon = tolerances.epsilon;
  auto start = std::chrono::steady_clock::now();
  std::vector<Index> welded_index;
  TriangleSoup welded = weld_identical_vertices(surface, welded_index);
  result.reoriented_faces = orient_coherently(welded).flipped;
  std::vector<std::array<Index, 2>> merges;
  for (const std::array<Index, 2>& merge : options.frozen_merges)
    merges.push_back({welded_index[merge[0]], welded_index[merge[1]]});
  MeshState state(reference, welded, tolerances, options.frozen_faces, merges);
  result.kept_aside_faces = state.kept_aside_faces();
  result.duplicate_faces = state.duplicate_faces();
  result.locked_vertices = state.locked_vertices();
  result.seconds_setup = seconds_since(start);

  start = std::chrono::steady_clock::now();
  result.collapses = collapse_edges(state, options.target_faces);
  result.seconds_collapse = seconds_since(start);

  start = std::chrono::steady_clock::now();
  result.flips = flip_edges(state, options.flip_passes);
  result.seconds_flip = seconds_since(start);

  result.soup = state.to_output();
  result.faces_after = result.soup.triangles.size();
  return result;
}

}  // namespace

SimplifyResult simplify_in_envelope(const TriangleSoup& input, const SimplifyOptions& options) {
  return simplify_in_envelope_of(input, input, options);
}

SimplifyResult simplify_in_envelope_of(const TriangleSoup& surface, const TriangleSoup& reference,
                                       const SimplifyOptions& options) {
  if (const std::string problem = find_soup_inconsistency(surface); !problem.empty())
    throw UsageError("simplify: inconsistent input soup: " + problem);
  if (const std::string problem = find_soup_inconsistency(reference); !problem.empty())
    throw UsageError("simplify: inconsistent reference soup: " + problem);
  if (!options.frozen_faces.empty() && options.frozen_faces.size() != surface.triangles.size())
    throw UsageError("simplify: " + std::to_string(options.frozen_faces.size()) + " frozen-face flags for " +
                     std::to_string(surface.triangles.size()) + " faces");
  for (const std::array<Index, 2>& merge : options.frozen_merges)
    if (merge[0] >= surface.positions.size() || merge[1] >= surface.positions.size())
      throw UsageError("simplify: a frozen merge names vertex " +
                       std::to_string(std::max(merge[0], merge[1])) + " of " +
                       std::to_string(surface.positions.size()));
  const DerivedTolerances tolerances = derive_tolerances(reference, options);
  if (surface.triangles.empty()) {
    SimplifyResult result;
    result.epsilon = tolerances.epsilon;
    return result;
  }
  if (!(tolerances.epsilon > 0.0))
    throw UsageError("simplify: epsilon is 0 (the input has a zero-size bounding box)");
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  return arena.execute([&] { return run(surface, reference, options, tolerances); });
}

}  // namespace mr::simplify
