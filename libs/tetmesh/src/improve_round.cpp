// Rounding the rational vertices left by triangle insertion: in place when
// the nearest doubles keep every incident tet positive, otherwise by moving
// the vertex a little, collapsing it onto a neighbour with double
// coordinates, or making room by smoothing its neighbours first.

#include "improve_local.h"

#include <mr/tetmesh/mesh_check.h>

#include <algorithm>
#include <string>

namespace mr::tetmesh::improve_detail {

bool try_round_in_place(Workspace& ws, Index v) {
  HybridPoint& position = ws.mesh.position(v);
  if (!position.is_exact()) return true;
  std::vector<Tet> tets;
  for (const Index t : ws.star(v)) tets.push_back(ws.mesh.tet(t));
  const HybridPoint rounded(position.approx);
  if (!all_positive(ws.mesh, tets, {v, &rounded})) return false;
  position.exact.reset();
  return true;
}

namespace {

// Neighbours of v, nearest first (ties by index); only those with double
// coordinates when `doubles_only`.
std::vector<Index> neighbours_by_distance(const Mesh& mesh, Index v, std::span<const Index> star,
                                          bool doubles_only) {
  std::vector<std::pair<double, Index>> found;
  for (const Index t : star) {
    for (const Index w : mesh.tet(t)) {
      if (w == v || (doubles_only && mesh.position(w).is_exact())) continue;
      found.emplace_back((mesh.position(w).approx - mesh.position(v).approx).squaredNorm(), w);
    }
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  std::vector<Index> out;
  for (const auto& entry : found) out.push_back(entry.second);
  return out;
}

bool round_one(Workspace& ws, Index v, RoundingStats& stats) {
  if (try_round_in_place(ws, v)) {
    ++stats.rounded;
    return true;
  }
  const std::vector<Index> star = ws.star(v);
  if (try_relocate(ws, v, star)) {
    ++stats.moved;
    return true;
  }
  for (const Index w : neighbours_by_distance(ws.mesh, v, star, true)) {
    if (try_collapse(ws, v, w, CollapseGoal::rounding)) {
      ++stats.collapsed;
      return true;
    }
  }
  return false;
}

// When v itself cannot move, its nearest neighbours are collapsed onto it,
// one at a time: each collapse takes away the faces of v's star that the
// rounded v would cross (a knot of cut points closer than a rounding step,
// or a sliver whose far face passes within one). Tried only on vertices the
// other moves left.
bool round_by_clearing_neighbours(Workspace& ws, Index v, RoundingStats& stats) {
  constexpr int kMaxCleared = 8;
  int cleared = 0;
  for (const Index w : neighbours_by_distance(ws.mesh, v, ws.star(v), false)) {
    if (cleared == kMaxCleared) break;
    if (!ws.mesh.vertex_alive(w)) continue;
    if (try_collapse(ws, w, v, CollapseGoal::rounding)) {
      ++cleared;
      ++stats.collapsed;
      if (round_one(ws, v, stats)) return true;
      continue;
    }
    // Two rational points of one knot: w may absorb v instead, and is
    // rounded in its own turn.
    if (ws.mesh.position(w).is_exact() && try_collapse(ws, v, w, CollapseGoal::rounding)) {
      ++stats.collapsed;
      return true;
    }
  }
  return false;
}

// Smooths the neighbours of v, which may open room for rounding it.
void smooth_neighbours(Workspace& ws, Index v) {
  std::vector<Index> neighbours;
  for (const Index t : ws.star(v)) {
    for (const Index w : ws.mesh.tet(t)) {
      if (w != v) neighbours.push_back(w);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  for (const Index w : neighbours) {
    const std::vector<Index> star = ws.star(w);
    try_smooth(ws, w, star);
  }
}

}  // namespace
}  // namespace mr::tetmesh::improve_detail

namespace mr::tetmesh {

RoundingStats round_vertices(Mesh& mesh, const SurfaceBounds& bounds, const Logger& logger) {
  using namespace improve_detail;
  constexpr int kRounds = 4;
  Workspace ws(mesh, &bounds.surface, 1.0, 10.0);
  ws.open_boundary = bounds.open_boundary;
  RoundingStats stats;
  std::vector<Index> rational;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (mesh.vertex_alive(v) && mesh.position(v).is_exact()) rational.push_back(v);
  }
  stats.rational_before = rational.size();
  for (int round = 0; round < kRounds && !rational.empty(); ++round) {
    std::vector<Index> left;
    for (const Index v : rational) {
      if (!mesh.vertex_alive(v) || !mesh.position(v).is_exact()) continue;
      if (round > 0) smooth_neighbours(ws, v);
      if (round_one(ws, v, stats)) continue;
      if (round > 0 && round_by_clearing_neighbours(ws, v, stats)) continue;
      left.push_back(v);
    }
    rational = std::move(left);
  }
  stats.remaining = rational.size();
  check_in_debug(mesh, "round_vertices");
  logger.log(stats.remaining == 0 ? LogLevel::debug : LogLevel::warning,
             "rounding: " + std::to_string(stats.rational_before) + " rational vertices, " +
                 std::to_string(stats.rounded) + " rounded, " + std::to_string(stats.moved) + " moved, " +
                 std::to_string(stats.collapsed) + " collapsed, " + std::to_string(stats.remaining) +
                 " left");
  return stats;
}

}  // namespace mr::tetmesh
