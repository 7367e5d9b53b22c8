#include "tet_removal.h"

#include <algorithm>
#include <tuple>

namespace mr::repair::detail {
namespace {

RemovalChoice evaluate(const TetMesh& mesh, const FaceNeighbours& neighbours,
                       const std::vector<std::uint8_t>& removed, const std::vector<Index>& tets,
                       const envelope::Envelope* envelope) {
  RemovalChoice choice;
  choice.tets = tets;
  for (Index t : tets) {
    choice.volume += tet_volume(mesh.positions, mesh.tets[t]);
    for (int k = 0; k < 4; ++k) {
      const Index other = neighbours.across(t, k);
      if (other == kNoTet || removed[other] || std::find(tets.begin(), tets.end(), other) != tets.end()) continue;
      const Triangle f = tet_face(mesh.tets[t], k);
      if (envelope && !envelope->is_inside(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]))
        ++choice.faces_outside;
    }
  }
  return choice;
}

}  // namespace

std::optional<RemovalChoice> choose_removal(const TetMesh& mesh, const FaceNeighbours& neighbours,
                                            const std::vector<std::uint8_t>& removed, std::size_t remaining,
                                            const std::vector<std::vector<Index>>& candidates,
                                            const envelope::Envelope* envelope) {
  std::optional<RemovalChoice> best;
  for (const std::vector<Index>& tets : candidates) {
    if (tets.empty() || tets.size() >= remaining) continue;
    RemovalChoice choice = evaluate(mesh, neighbours, removed, tets, envelope);
    if (!best || std::tie(choice.faces_outside, choice.volume) < std::tie(best->faces_outside, best->volume))
      best = std::move(choice);
  }
  return best;
}

}  // namespace mr::repair::detail
