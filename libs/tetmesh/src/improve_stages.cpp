#include "improve_stages.h"

#include <algorithm>

namespace mr::tetmesh::improve_detail {
namespace {

// A deeper floor follows only while few tets (kFewBadShare of those that
// count, or this many) are bad. A deeper floor from the start refined
// whole meshes (trimesh/soup and openscad-nonmanifold-crash past 300 s at
// 1/20 of the target).
constexpr double kDeepenTets = 500;

// A stage that ends this many times above the best one's largest energy
// starts no deeper one: trimesh/suzanne ended at 16.9 on the first floor,
// 1,184 on the second and 644,226 (9,595 bad tets) on the third. A stage
// a little worse may still lead to a better one (trimesh/CesiumMilkTruck:
// 20.9, 24.4, then 15.4 and 14.2).
constexpr double kLostStage = 2;

}  // namespace

EnergyState energy_state(const Workspace& ws, std::span<const double> energy) {
  EnergyState out;
  double sum = 0;
  const double stop_energy = ws.stop_energy;
  for (Index t = 0; t < energy.size(); ++t) {
    if (!ws.mesh.tet_alive(t) || !ws.drives(t)) continue;
    out.max = std::max(out.max, energy[t]);
    out.bad += energy[t] >= stop_energy;
    sum += energy[t];
    ++out.tets;
  }
  out.mean = out.tets ? sum / double(out.tets) : 0.0;
  return out;
}

bool FloorStages::may_deepen(const EnergyState& state) const {
  const double few = std::max(kFewBadShare * double(state.tets), kDeepenTets);
  return hit_ && halvings_ < max_halvings_ && double(state.bad) <= few;
}

bool FloorStages::deepen(const Workspace& ws, std::span<const EnergyState> history) {
  const EnergyState& state = history.back();
  if (best_ && !(state.max <= kLostStage * best_state_.max)) return false;
  if (!best_ || state.max < best_state_.max) {
    best_.emplace(ws);
    best_state_ = state;
  }
  floor_ /= 2, ++halvings_, hit_ = false;
  start_ = history.size() - 1;
  return true;
}

bool FloorStages::restore_best(Workspace& ws, const EnergyState& last) {
  if (!best_ || !(best_state_.max < last.max)) return false;
  std::move(*best_).restore(ws);
  return true;
}

}  // namespace mr::tetmesh::improve_detail
