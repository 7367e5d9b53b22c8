// The improvement loop: passes of split, collapse, swap and smoothing until
// the largest AMIPS energy is below the stop energy, refining the local
// target length around tets that stay bad.

#include "improve_local.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/mesh_check.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace mr::tetmesh {
namespace {

using namespace improve_detail;

struct QualityTally {
  std::size_t tets = 0;
  double min_dihedral = 180, sum_min_dihedral = 0, max_amips = 0, sum_amips = 0;

  void add(const QualityTally& o) {
    tets += o.tets;
    min_dihedral = std::min(min_dihedral, o.min_dihedral);
    sum_min_dihedral += o.sum_min_dihedral;
    max_amips = std::max(max_amips, o.max_amips);
    sum_amips += o.sum_amips;
  }
};

double max_tet_energy(const Mesh& mesh) {
  const std::vector<double> energy = tet_energies(mesh);
  return energy.empty() ? 0.0 : *std::max_element(energy.begin(), energy.end());
}

void validate(const ImproveOptions& options) {
  if (!(options.target_edge_length > 0) || !std::isfinite(options.target_edge_length)) {
    throw UsageError("improve_mesh: the target edge length must be positive and finite");
  }
  if (!(options.stop_energy > 0) || !std::isfinite(options.stop_energy)) {
    throw UsageError("improve_mesh: the stop energy must be positive and finite");
  }
  if (options.max_passes < 0 || options.threads < 0 || options.max_refinements < 0) {
    throw UsageError("improve_mesh: max_passes, threads and max_refinements must not be negative");
  }
}

// Halves the local target around tets still above the stop energy (never
// below 2^-max_refinements of the global target). Returns the vertices refined.
std::size_t refine_bad_regions(Workspace& ws, int max_refinements) {
  const double smallest = std::ldexp(1.0, -max_refinements);
  const std::vector<double> energy = tet_energies(ws.mesh);
  std::vector<char> refine(ws.mesh.vertex_slots(), 0);
  for (Index t = 0; t < ws.mesh.tet_slots(); ++t) {
    if (!ws.mesh.tet_alive(t) || energy[t] < ws.stop_energy) continue;
    for (const Index v : ws.mesh.tet(t)) refine[v] = 1;
  }
  std::size_t count = 0;
  for (Index v = 0; v < refine.size(); ++v) {
    if (!refine[v] || ws.sizing[v] <= smallest) continue;
    ws.sizing[v] = std::max(smallest, ws.sizing[v] * 0.5);
    ++count;
  }
  return count;
}

std::size_t round_in_place(Workspace& ws) {
  std::size_t left = 0;
  for (Index v = 0; v < ws.mesh.vertex_slots(); ++v) {
    if (ws.mesh.vertex_alive(v) && ws.mesh.position(v).is_exact() && !try_round_in_place(ws, v)) ++left;
  }
  return left;
}

std::string pass_summary(int pass, const ImproveStats& s, double max_energy) {
  std::ostringstream text;
  text << "improve pass " << pass << ": " << s.splits << " splits, " << s.collapses << " collapses, "
       << s.swaps_32 + s.swaps_23 + s.swaps_44 << " swaps, " << s.smoothing_moves
       << " smoothing moves so far; max AMIPS " << max_energy;
  return text.str();
}

ImproveStats run_passes(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                        const Logger& logger) {
  ImproveStats stats;
  stats.before = measure_quality(mesh);
  Workspace ws(mesh, &bounds.surface, options.target_edge_length, options.stop_energy);
  ws.open_boundary = bounds.open_boundary;
  double max_energy = stats.before.max_amips;
  int refinements = 0;
  for (int pass = 0; pass < options.max_passes && max_energy >= options.stop_energy; ++pass) {
    const std::size_t splits = split_pass(ws);
    check_in_debug(mesh, "improve: split");
    const std::size_t collapses = collapse_pass(ws);
    check_in_debug(mesh, "improve: collapse");
    const SwapCounts swaps = swap_pass(ws);
    check_in_debug(mesh, "improve: swap");
    const std::size_t moves = smooth_pass(ws);
    check_in_debug(mesh, "improve: smooth");
    stats.rational_vertices = round_in_place(ws);
    stats.splits += splits;
    stats.collapses += collapses;
    stats.swaps_32 += swaps.s32;
    stats.swaps_23 += swaps.s23;
    stats.swaps_44 += swaps.s44;
    stats.smoothing_moves += moves;
    stats.passes = pass + 1;

    const double previous = max_energy;
    max_energy = max_tet_energy(mesh);
    logger.log(LogLevel::debug, pass_summary(pass + 1, stats, max_energy));
    logger.progress("improve", double(pass + 1) / options.max_passes);
    // Written so that an energy stuck at infinity (a tet flat on the doubles)
    // also counts as stalled: inf > 0.99 * inf is false.
    const bool stalled = !(max_energy < 0.99 * previous);
    if (stalled && max_energy >= options.stop_energy) {
      if (refinements >= options.max_refinements) break;
      ++refinements;
      stats.refinements += refine_bad_regions(ws, options.max_refinements);
    }
  }
  stats.rational_vertices = round_in_place(ws);
  stats.after = measure_quality(mesh);
  return stats;
}

}  // namespace

QualitySummary measure_quality(const Mesh& mesh) {
  const QualityTally total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<Index>(0, Index(mesh.tet_slots()), 1024), QualityTally{},
      [&](const tbb::blocked_range<Index>& range, QualityTally acc) {
        for (Index t = range.begin(); t != range.end(); ++t) {
          if (!mesh.tet_alive(t)) continue;
          const Tet& c = mesh.tet(t);
          const Vec3d &a = mesh.position(c[0]).approx, &b = mesh.position(c[1]).approx,
                      &p = mesh.position(c[2]).approx, &d = mesh.position(c[3]).approx;
          const double dihedral = check::min_dihedral_angle_deg(a, b, p, d);
          const double amips = tet_energy(mesh, t);
          ++acc.tets;
          acc.min_dihedral = std::min(acc.min_dihedral, dihedral);
          acc.sum_min_dihedral += dihedral;
          acc.max_amips = std::max(acc.max_amips, amips);
          acc.sum_amips += amips;
        }
        return acc;
      },
      [](QualityTally x, const QualityTally& y) {
        x.add(y);
        return x;
      });
  QualitySummary out;
  out.tets = total.tets;
  if (total.tets == 0) return out;
  out.min_dihedral_deg = total.min_dihedral;
  out.avg_min_dihedral_deg = total.sum_min_dihedral / double(total.tets);
  out.max_amips = total.max_amips;
  out.avg_amips = total.sum_amips / double(total.tets);
  return out;
}

ImproveStats improve_mesh(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                          const Logger& logger) {
  validate(options);
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  ImproveStats stats;
  arena.execute([&] { stats = run_passes(mesh, bounds, options, logger); });
  std::ostringstream text;
  text << "improve: " << stats.passes << " passes, max AMIPS " << stats.before.max_amips << " -> "
       << stats.after.max_amips << ", min dihedral " << stats.before.min_dihedral_deg << " -> "
       << stats.after.min_dihedral_deg << " deg, " << stats.rational_vertices << " rational vertices left";
  logger.log(LogLevel::info, text.str());
  return stats;
}

}  // namespace mr::tetmesh
