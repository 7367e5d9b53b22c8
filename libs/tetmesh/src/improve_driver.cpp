// The improvement loop: passes of split, collapse, swap and smoothing until
// the largest AMIPS energy is below the stop energy, refining the local
// target length around tets that stay bad.

#include "improve_stages.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/incidence.h>
#include <mr/tetmesh/mesh_check.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
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

void validate(const ImproveOptions& options) {
  if (!(options.target_edge_length > 0) || !std::isfinite(options.target_edge_length)) {
    throw UsageError("improve_mesh: the target edge length must be positive and finite");
  }
  if (!(options.stop_energy > 0) || !std::isfinite(options.stop_energy)) {
    throw UsageError("improve_mesh: the stop energy must be positive and finite");
  }
  if (options.max_passes < 0 || options.threads < 0 || options.floor_halvings < 0) {
    throw UsageError("improve_mesh: max_passes, threads and floor_halvings must not be negative");
  }
  if (!(options.min_sizing > 0 && options.min_sizing <= 1)) {
    throw UsageError("improve_mesh: min_sizing must be in (0, 1]");
  }
}

// A pass stalls when it lowers the largest energy by less than half a unit
// and the mean by less than 10% (written so that a largest energy stuck at
// infinity, a tet flat on the doubles, stalls too).
bool stalled(const EnergyState& before, const EnergyState& after) {
  return !(before.max - after.max >= 0.5) && !(before.mean - after.mean >= 0.1 * before.mean);
}

// After the local target reached its floor somewhere, improvement ends once
// the largest energy went down by less than 1% over this many passes (the
// mean keeps moving a little as splits and collapses trade places).
constexpr std::size_t kPatience = 5;

// Improvement also ends, floor or not, once this many passes brought the
// largest energy down by less than 1%. The local target shrinks only when
// a pass stalls, lowering the largest energy by less than half a unit; at
// energies of a million a pass always does more than that, so the floor
// was never reached: thingi10k/55581 (264 faces) ran all 80 passes in
// 71 s, its largest energy going from 749,669 after pass 23 to 714,043.
constexpr std::size_t kLongPatience = 10;

// Whether the best largest energy of the last `patience` passes is 1% below
// the best before them. A best, not the last pass's: a split can make a
// tet worse for a pass (teapot: 26.7, then 14,931, then 17.7).
bool improved_lately(std::span<const EnergyState> history, std::size_t patience) {
  if (history.size() <= patience + 1) return true;
  const auto best = [](std::span<const EnergyState> passes) {
    double lowest = std::numeric_limits<double>::infinity();
    for (const EnergyState& s : passes) lowest = std::min(lowest, s.max);
    return lowest;
  };
  const std::size_t split = history.size() - patience;
  return best(history.subspan(split)) < 0.99 * best(history.first(split));
}

std::size_t round_in_place(Workspace& ws) {
  std::size_t left = 0;
  for (Index v = 0; v < ws.mesh.vertex_slots(); ++v) {
    if (ws.mesh.vertex_alive(v) && ws.mesh.position(v).is_exact() && !try_round_in_place(ws, v)) ++left;
  }
  return left;
}

std::string pass_summary(int pass, const ImproveStats& s, const EnergyState& state) {
  std::ostringstream text;
  text << "improve pass " << pass << ": " << s.splits << " splits, " << s.collapses << " collapses, "
       << s.swaps_32 + s.swaps_23 + s.swaps_44 + s.edge_removals << " swaps, " << s.smoothing_moves
       << " smoothing moves so far; max AMIPS " << state.max << ", mean " << state.mean << ", " << state.bad
       << " tets at or above the stop energy";
  return text.str();
}

// With a sizing field, the mesh may be far from its lengths while its
// energy is already low: passes go on until one changes the number of tets
// by at most this share (fTetWild's criterion after applying its field;
// splits and collapses keep trading places at the ends of the length
// window, so their count does not settle).
constexpr double kSettledShare = 0.02;

bool sizing_settled(const ImproveOptions& options, std::size_t tets_before, std::size_t tets_after) {
  const double change = std::abs(double(tets_after) - double(tets_before));
  return options.sizing == nullptr || change <= kSettledShare * double(tets_before);
}

// Once few tets are bad (kFewBadShare, at or above the stop
// energy), a pass works only within kFocusRings rings of their corners:
// elsewhere the mesh is good already, and whole passes for the last few bad
// tets took most of the time (c3d/igea: 7 of its 14 passes for a largest
// energy between 10.2 and 10.7). The first kWholePasses passes, and every
// pass under a sizing field, see the whole mesh: they bring the lengths to
// their targets.
constexpr int kFocusRings = 2;
constexpr int kWholePasses = 4;

// Sets ws.focus for the next pass from the energies after the last one.
void set_focus(Workspace& ws, std::span<const double> energy, bool whole) {
  ws.focus.clear();
  if (whole) return;
  const Mesh& mesh = ws.mesh;
  std::size_t driving = 0, bad = 0;
  std::vector<char> focus(mesh.vertex_slots(), 0);
  std::vector<Index> frontier;  // the vertices the last ring added
  const auto add = [&](Index v, std::vector<Index>& to) {
    if (focus[v] == 0) focus[v] = 1, to.push_back(v);
  };
  for (Index t = 0; t < energy.size(); ++t) {
    if (!mesh.tet_alive(t) || !ws.drives(t)) continue;
    ++driving;
    if (energy[t] < ws.stop_energy) continue;
    ++bad;
    for (const Index v : mesh.tet(t)) add(v, frontier);
  }
  if (double(bad) > kFewBadShare * double(driving)) return;
  const VertexTets incidence(mesh);
  for (int ring = 0; ring < kFocusRings; ++ring) {
    std::vector<Index> next;
    for (const Index v : frontier)
      for (const Index t : incidence.of(v))
        for (const Index w : mesh.tet(t)) add(w, next);
    frontier = std::move(next);
  }
  ws.focus = std::move(focus);
}

// One pass of every operation; without splits (`split` false) none raises the largest energy of
// the tets that count above max(it, stop energy), but for pinches (improve_collapse.cpp).
// A pass without splits is a polish (see polish): its smoothing lowers a soft maximum of the
// energies around a bad tet, not their sum, since a polish keeps a pass only if it lowers the
// largest energy. In every pass, or once few tets were bad, the soft maximum sent the passes
// elsewhere, better on some models and worse on others (thingi10k/55581 18.9 -> 10.0,
// thingi10k/96582 30.5 -> 6,048; a cube and a grazing copy, open, 12.9 -> 18.4).
void run_pass(Workspace& ws, ImproveStats& stats, bool split = true) {
  const std::size_t splits = split ? split_pass(ws) : 0;
  check_in_debug(ws.mesh, "improve: split");
  const std::size_t collapses = collapse_pass(ws);
  check_in_debug(ws.mesh, "improve: collapse");
  const SwapCounts swaps = swap_pass(ws);
  check_in_debug(ws.mesh, "improve: swap");
  const std::size_t moves = smooth_pass(ws, /*soft_max=*/!split);
  check_in_debug(ws.mesh, "improve: smooth");
  stats.rational_vertices = round_in_place(ws);
  stats.splits += splits;
  stats.collapses += collapses;
  stats.swaps_32 += swaps.s32;
  stats.swaps_23 += swaps.s23;
  stats.swaps_44 += swaps.s44;
  stats.edge_removals += swaps.removals;
  stats.smoothing_moves += moves;
}

// A split leaves tets worse for a pass until the other operations repair them, so passes can end
// on a bad pass (trimesh/suzanne: largest energy 15.7 after pass 18, 4,978 after pass 19, 353 when
// they ended). Where they end above the stop energy, passes without splits follow while each lowers
// the largest energy by 1%, and the best mesh they passed through is kept. Even without splits the
// largest energy of the written tets can rise: an operation compares the tets that count, beside
// the written ones too, and a pinch may raise it (suzanne: 18.4, then 98.1).
constexpr int kMaxPolishPasses = 10;

// `energy`: per tet slot, after the last pass. Returns the energies of the mesh it leaves.
std::vector<double> polish(Workspace& ws, ImproveStats& stats, std::vector<EnergyState>& history,
                           std::vector<double> energy, const Logger& logger) {
  if (history.back().max < ws.stop_energy) return energy;
  std::optional<Snapshot> best;
  double best_max = history.back().max;
  for (int pass = 0; pass < kMaxPolishPasses && best_max >= ws.stop_energy; ++pass) {
    if (!best) best.emplace(ws);
    set_focus(ws, energy, ws.has_sizing_field());
    run_pass(ws, stats, false);
    ++stats.polish_passes;
    energy = tet_energies(ws, true);
    const EnergyState state = energy_state(ws, energy);
    logger.log(LogLevel::debug,
               "polish " + std::to_string(pass + 1) + " after " + pass_summary(stats.passes, stats, state));
    history.push_back(state);
    if (!(state.max < 0.99 * best_max)) break;
    best_max = state.max;
    best.reset();  // the current mesh is the best: taken again before the next pass
  }
  if (best) {
    std::move(*best).restore(ws);
    energy = tet_energies(ws, true);
    history.push_back(energy_state(ws, energy));
  }
  return energy;
}

// How many of the tets left at or above the stop energy the stats name.
constexpr std::size_t kWorstReported = 10;

std::string floor_summary(const FloorStages& floor, const EnergyState& state) {
  std::ostringstream text;
  text << "improve: the local target's floor halves to " << floor.floor() << " of the target, from max AMIPS "
       << state.max << " with " << state.bad << " tets at or above the stop energy";
  return text.str();
}

// Passes until the largest energy is below the stop energy (and, with a
// sizing field, the lengths settled). When a pass stalls, the local target
// shrinks around the bad tets (never two passes in a row, so that the
// splits it causes can settle); once it reached its floor and kPatience
// passes brought nothing, the floor deepens (FloorStages) or improvement
// ends; kLongPatience passes that brought nothing end it anyway.
ImproveStats run_passes(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                        TetPayload& payload, const Logger& logger) {
  ImproveStats stats;
  stats.before = measure_quality(mesh);
  Workspace ws(mesh, &bounds.surface, options.target_edge_length, options.stop_energy);
  ws.open_boundary = bounds.open_boundary;
  ws.triangles = bounds.triangles;
  ws.payload = std::move(payload);
  ws.release_junctions = options.release_junctions;
  const Workspace::FieldSamples samples = ws.use_sizing_field(options.sizing);
  stats.sizing_outside = samples.outside;
  stats.sizing_clamped = samples.clamped;
  if (options.sizing != nullptr) ws.collapse_below = 2.0 / 3.0;
  std::vector<double> energy = tet_energies(ws, true);
  std::vector<EnergyState> history{energy_state(ws, energy)};
  bool just_resized = false, settled = options.sizing == nullptr;
  FloorStages floor(options.min_sizing, options.floor_halvings);
  for (int pass = 0; pass < options.max_passes && (history.back().max >= options.stop_energy || !settled);
       ++pass) {
    const std::size_t tets_before = mesh.num_tets();
    set_focus(ws, energy, pass < kWholePasses || options.sizing != nullptr);
    run_pass(ws, stats);
    settled = sizing_settled(options, tets_before, mesh.num_tets());
    stats.passes = pass + 1;
    energy = tet_energies(ws, true);
    const EnergyState state = energy_state(ws, energy);
    logger.log(LogLevel::debug, pass_summary(pass + 1, stats, state));
    logger.progress("improve", double(pass + 1) / options.max_passes);
    const bool resize = !just_resized && stalled(history.back(), state);
    history.push_back(state);
    just_resized = resize;
    if (resize) {
      const SizingUpdate update = update_sizing(ws, energy, state.max, floor.floor());
      stats.refinements += update.shrunk;
      floor.note_shrink(update);
    }
    const std::size_t patience = floor.hit_floor() ? kPatience : kLongPatience;
    if (improved_lately(floor.stage(history), patience)) continue;
    if (!floor.may_deepen(state)) break;
    // Each stage ends polished, as the last: a stage stuck just above the
    // stop energy is often polished below it.
    energy = polish(ws, stats, history, std::move(energy), logger);
    if (history.back().max < options.stop_energy || !floor.deepen(ws, history)) break;
    logger.log(LogLevel::debug, floor_summary(floor, history.back()));
  }
  stats.floor_halvings = floor.halvings();
  stats.passes_max_amips = history.back().max;
  polish(ws, stats, history, std::move(energy), logger);
  if (floor.restore_best(ws, history.back())) {
    history.push_back(energy_state(ws, tet_energies(ws, true)));
    ++stats.floor_stages_undone;
  }
  ws.focus.clear();
  stats.rational_vertices = round_in_place(ws);
  stats.after = measure_quality(mesh);
  stats.written_max_amips = history.back().max;
  stats.stuck = stuck_report(ws, tet_energies(ws, true), kWorstReported);
  payload = std::move(ws.payload);
  if (!payload.fate.empty()) payload.fate.resize(mesh.tet_slots(), kWritten);
  if (!payload.value.empty()) payload.value.resize(mesh.tet_slots(), 0.0);
  return stats;
}

std::string stuck_summary(const StuckReport& stuck) {
  const StuckTet& worst = stuck.worst.front();
  std::ostringstream text;
  text << "improve: " << stuck.tets << " tets to be written stay at or above the stop energy: " << stuck.free
       << " with a corner free to move, " << stuck.sliding << " with every corner on the surface, "
       << stuck.creased << " on its creases or open boundary, " << stuck.fixed
       << " with every corner fixed; the worst, AMIPS " << worst.amips << ", at (" << worst.centroid[0]
       << ", " << worst.centroid[1] << ", " << worst.centroid[2] << ")";
  return text.str();
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
  TetPayload none;
  return improve_mesh(mesh, bounds, options, none, logger);
}

ImproveStats improve_mesh(Mesh& mesh, const SurfaceBounds& bounds, const ImproveOptions& options,
                          TetPayload& payload, const Logger& logger) {
  validate(options);
  const auto wrong_size = [&](std::size_t n) { return n != 0 && n != mesh.tet_slots(); };
  if (wrong_size(payload.fate.size()) || wrong_size(payload.value.size())) {
    throw UsageError("improve_mesh: the payload must have one entry per tet slot");
  }
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  ImproveStats stats;
  arena.execute([&] { stats = run_passes(mesh, bounds, options, payload, logger); });
  std::ostringstream text;
  text << "improve: " << stats.passes << " passes, max AMIPS " << stats.before.max_amips << " -> "
       << stats.after.max_amips << " (" << stats.written_max_amips
       << " over the tets to be written), min dihedral " << stats.before.min_dihedral_deg << " -> "
       << stats.after.min_dihedral_deg << " deg, " << stats.rational_vertices << " rational vertices left";
  if (stats.polish_passes > 0) {
    text << "; " << stats.polish_passes
         << " passes without splits took the written tets' largest energy from " << stats.passes_max_amips
         << " to " << stats.written_max_amips;
  }
  logger.log(LogLevel::info, text.str());
  if (stats.stuck.tets > 0) logger.log(LogLevel::info, stuck_summary(stats.stuck));
  if (options.sizing != nullptr) {
    std::ostringstream field;
    field
        << "improve: the sizing field gave no value at " << stats.sizing_outside
        << " vertices (the global target held there) and one beyond [1/100, 100] times the global target at "
        << stats.sizing_clamped << " (clamped)";
    logger.log(stats.sizing_outside + stats.sizing_clamped > 0 ? LogLevel::info : LogLevel::debug,
               field.str());
  }
  return stats;
}

}  // namespace mr::tetmesh
