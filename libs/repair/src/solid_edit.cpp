#include "solid_edit.h"

#include <algorithm>
#include <tuple>

namespace mr::repair::detail {
namespace {

bool contains(const std::vector<Index>& sorted, Index t) {
  return std::binary_search(sorted.begin(), sorted.end(), t);
}

// Is face k of tet t on the boundary once the edit is made? Removed tets
// expose the faces they share with the solid; added tets bring the faces
// they do not share with it.
bool on_boundary_after(const FaceNeighbours& neighbours, std::span<const TetState> states,
                       const SolidEdit& edit, Index t, int k) {
  const Index other = neighbours.across(t, k);
  if (edit.add) return other == kNoTet || (!in_solid(states[other]) && !contains(edit.tets, other));
  return other != kNoTet && in_solid(states[other]) && !contains(edit.tets, other);
}

SolidEdit evaluate(const TetMesh& mesh, const FaceNeighbours& neighbours, std::span<const TetState> states,
                   const std::vector<Index>& tets, const envelope::Envelope* envelope) {
  SolidEdit edit;
  edit.tets = tets;
  std::sort(edit.tets.begin(), edit.tets.end());
  edit.add = !in_solid(states[tets.front()]);
  for (Index t : edit.tets) {
    edit.volume += tet_volume(mesh.positions, mesh.tets[t]);
    for (int k = 0; k < 4; ++k) {
      if (!on_boundary_after(neighbours, states, edit, t, k)) continue;
      const Triangle f = tet_face(mesh.tets[t], k);
      if (envelope && !envelope->is_inside(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]))
        ++edit.faces_outside;
    }
  }
  return edit;
}

// All in the solid (a removal), or all rejected (an addition).
bool may_change(std::span<const TetState> states, const std::vector<Index>& tets) {
  if (std::all_of(tets.begin(), tets.end(), [&](Index t) { return in_solid(states[t]); })) return true;
  return std::all_of(tets.begin(), tets.end(), [&](Index t) { return states[t] == TetState::rejected; });
}

}  // namespace

std::optional<SolidEdit> choose_edit(const TetMesh& mesh, const FaceNeighbours& neighbours,
                                     std::span<const TetState> states, std::size_t solid_tets,
                                     const std::vector<std::vector<Index>>& candidates,
                                     const envelope::Envelope* envelope) {
  std::optional<SolidEdit> best;
  for (const std::vector<Index>& tets : candidates) {
    if (tets.empty() || !may_change(states, tets)) continue;
    if (in_solid(states[tets.front()]) && tets.size() >= solid_tets) continue;
    SolidEdit edit = evaluate(mesh, neighbours, states, tets, envelope);
    if (!best || std::tie(edit.faces_outside, edit.volume) < std::tie(best->faces_outside, best->volume))
      best = std::move(edit);
  }
  return best;
}

}  // namespace mr::repair::detail
