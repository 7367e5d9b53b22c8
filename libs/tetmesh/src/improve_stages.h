// What the improvement passes keep between them (improve_driver.cpp): the
// energy after each pass, a copy of the mesh to go back to, and the floor
// of the local target, lowered in stages.

#pragma once

#include "improve_local.h"

#include <optional>
#include <span>
#include <vector>

namespace mr::tetmesh::improve_detail {

/// "Few bad tets": at most this share of the tets that count are at or
/// above the stop energy. Passes then work around them only
/// (improve_driver.cpp), and the refinement floor may deepen around them.
inline constexpr double kFewBadShare = 0.01;

/// The largest and mean energy of the tets that count, how many there are,
/// and how many of them are at or above the stop energy.
struct EnergyState {
  double max = 0, mean = 0;
  std::size_t bad = 0, tets = 0;
};

/// `energy`: per tet slot.
EnergyState energy_state(const Workspace& ws, std::span<const double> energy);

/// A copy of what the passes change, to go back to.
struct Snapshot {
  Mesh mesh;
  TetPayload payload;
  std::vector<double> sizing, field_scale;

  explicit Snapshot(const Workspace& ws)
      : mesh(ws.mesh), payload(ws.payload), sizing(ws.sizing), field_scale(ws.field_scale) {}
  void restore(Workspace& ws) && {
    ws.mesh = std::move(mesh);
    ws.payload = std::move(payload);
    ws.sizing = std::move(sizing);
    ws.field_scale = std::move(field_scale);
    ws.reset_seeds();
  }
};

/// The floor of the local target, lowered in stages, and the best mesh a
/// stage ended on: a deeper stage can end worse than the one before it,
/// and then that one's mesh is written. Once the target reached its floor
/// and the passes brought nothing, the floor halves (at most `halvings`
/// times) while the bad tets are few: the target then shrinks only around
/// them, where a thin part, a sharp crease or two close sheets need edges
/// shorter than the floor, and the rest keeps its lengths.
class FloorStages {
 public:
  FloorStages(double floor, int halvings) : floor_(floor), max_halvings_(halvings) {}
  double floor() const { return floor_; }
  int halvings() const { return halvings_; }
  bool hit_floor() const { return hit_; }
  void note_shrink(const SizingUpdate& update) { hit_ |= update.hit_floor; }
  /// The passes of the current stage, from the one it started after.
  std::span<const EnergyState> stage(std::span<const EnergyState> history) const {
    return history.subspan(start_);
  }
  /// Whether a deeper stage may follow the current one, stalled at `state`.
  bool may_deepen(const EnergyState& state) const;
  /// Starts the next stage on the mesh as it is (polished), kept to be
  /// restored at the end if it is the best so far and no later stage ends
  /// better; returns false, and starts none, if the current stage ended
  /// far worse than the best.
  bool deepen(const Workspace& ws, std::span<const EnergyState> history);
  /// Restores the best stage's mesh if the last stage ended worse; returns
  /// whether it did.
  bool restore_best(Workspace& ws, const EnergyState& last);

 private:
  double floor_;
  int max_halvings_;
  int halvings_ = 0;
  std::size_t start_ = 0;
  bool hit_ = false;
  std::optional<Snapshot> best_;
  EnergyState best_state_;
};

}  // namespace mr::tetmesh::improve_detail
