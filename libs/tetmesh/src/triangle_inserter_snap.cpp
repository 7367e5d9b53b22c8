// Stage 4, before cutting: cut points of earlier polygons that lie very
// near the plane P of the polygon being inserted are moved onto it (see
// triangle_inserter.h). Adjacent triangles of a finely curved surface are
// nearly coplanar, so each plane passes within a millionth of the bbox of
// the cut points its neighbours' planes made (thingi10k/55581: 12,817 of
// 15,796 cut points). Cut there, the edges at such a point get a new point
// next to it, and the knots of points left behind are flat tets that no
// collapse can untie. fTetWild snaps such points onto the plane too (its
// eps_coplanar); here the move is exact and checked exactly: the point
// lands on P, and every tet around it stays positive.

#include "triangle_inserter.h"

#include <mr/kernel/constructions.h>
#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <cmath>

namespace mr::tetmesh::detail {

void TriangleInserter::forget_candidates() {
  ++generation_;  // unstamps every tet and forgets every vertex's sides
  plane_points_.clear();
  candidates_.clear();
  cut_tets_.clear();
}

// Moves the cut points among the candidates' corners that lie within the
// snap distance of P onto it; returns how many moved. The distance on
// doubles only chooses which points to try: each move is decided exactly
// (try_move_onto_plane).
std::size_t TriangleInserter::snap_points_near_plane() {
  std::vector<Index> corners;
  for (const Index t : candidates_) {
    for (const Index v : mesh_.tet(t)) {
      if (v < creator_.size() && creator_[v] != kNoCreator) corners.push_back(v);
    }
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  const Vec3d& a = mesh_.position(corners_[0]).approx;
  const Vec3d normal =
      (mesh_.position(corners_[1]).approx - a).cross(mesh_.position(corners_[2]).approx - a).normalized();
  std::size_t moved = 0;
  for (const Index v : corners) {
    if (std::abs(normal.dot(mesh_.position(v).approx - a)) >= snap_distance_ || plane_sign(v) == 0) continue;
    moved += try_move_onto_plane(v) ? 1 : 0;
  }
  counters_.snapped_points += moved;
  return moved;
}

// Moves cut point v onto P along the projection axis when it is on no
// tracked face and not on the hull (both must keep their planes), its
// coordinates stay within the exact budget and every tet around it stays
// positive.
bool TriangleInserter::try_move_onto_plane(Index v) {
  const Index seed = v < seed_tet_.size() ? seed_tet_[v] : kNoTet;
  if (seed == kNoTet || !mesh_.tet_alive(seed) || mesh_.corner_of(seed, v) < 0) return false;
  const std::vector<Index> star = tets_around_vertex(mesh_, v, seed);
  for (const Index t : star) {
    for (int f = 0; f < 4; ++f) {
      if (mesh_.tet(t)[f] == v) continue;  // the face opposite v does not move
      if (mesh_.is_surface_face(t, f) || mesh_.neighbour(t, f) == kNoTet) return false;
    }
  }
  const ExactPoint3 onto =
      move_onto_plane_along_axis(mesh_.position(v), axis_, mesh_.position(corners_[0]),
                                 mesh_.position(corners_[1]), mesh_.position(corners_[2]));
  if (bit_size(onto) > max_exact_bits_) return false;
  const HybridPoint moved = HybridPoint::from_exact(onto);
  for (const Index t : star) {
    const Tet& c = mesh_.tet(t);
    const auto at = [&](Index x) -> const HybridPoint& { return x == v ? moved : mesh_.position(x); };
    if (orient3d(at(c[0]), at(c[1]), at(c[2]), at(c[3])) <= 0) return false;
  }
  mesh_.position(v) = moved;
  return true;
}

}  // namespace mr::tetmesh::detail
