// Stage 4 for one polygon (see triangle_inserter.h): the cut points, the
// split faces and the cavity; the plane tests are in
// triangle_inserter_plane.cpp, the rebuilding in triangle_inserter_cavity.cpp.

#include "triangle_inserter.h"

#include "inserter_keys.h"

#include <mr/core/errors.h>
#include <mr/kernel/constructions.h>

#include <algorithm>

namespace mr::tetmesh::detail {

TriangleInserter::TriangleInserter(Mesh& mesh, std::size_t max_exact_bits, double snap_distance, bool settle)
    : mesh_(mesh), max_exact_bits_(max_exact_bits), snap_distance_(snap_distance), settle_(settle) {
  seed_tet_.assign(mesh.vertex_slots(), kNoTet);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (Index v : mesh.tet(t)) seed_tet_[v] = t;
  }
}

bool TriangleInserter::stamped(std::vector<std::uint32_t>& stamps, Index t) const {
  return t < stamps.size() && stamps[t] == generation_;
}

void TriangleInserter::stamp(std::vector<std::uint32_t>& stamps, Index t) {
  if (stamps.size() <= t) stamps.resize(std::max<std::size_t>(t + 1, mesh_.tet_slots()), 0);
  stamps[t] = generation_;
}

void TriangleInserter::note_new_vertex(Index v) {
  if (seed_tet_.size() <= v) seed_tet_.resize(v + 1, kNoTet);
  if (creator_.size() <= v) creator_.resize(v + 1, kNoCreator);
  creator_[v] = id_;
}

// ------------------------------------------------------------------ cutting

// The new point on segment (u, v) where P (line < 0) or the line through
// T's edge `line` crosses it; created once, shared by every polygon that has
// the segment. A segment between two old vertices is a mesh edge: every tet
// around it must then be rebuilt.
Index TriangleInserter::split_point(Index u, Index v, int line, Index seed_tet) {
  const auto [it, inserted] = splits_.try_emplace(segment_key(u, v), kNoVertex);
  if (!inserted) return it->second;
  const HybridPoint& pu = mesh_.position(u);
  const HybridPoint& pv = mesh_.position(v);
  const Index w = mesh_.add_vertex(
      line < 0 ? plane_point(u, v)
               : HybridPoint::from_exact(intersect_segment_plane(
                     pu, pv, mesh_.position(corners_[line]),
                     mesh_.position(corners_[(line + 1) % line_count()]), line_lift_[line])));
  note_new_vertex(w);
  it->second = w;
  if (new_vertices_.count(u) == 0 && new_vertices_.count(v) == 0) {
    split_mesh_edges_.push_back({u, v, seed_tet});
  }
  new_vertices_.insert(w);
  ++counters_.new_vertices;
  return w;
}

void TriangleInserter::register_cut_points() {
  for (Index t : cut_tets_) {
    const Tet& c = mesh_.tet(t);
    for (const auto& [i, j] : kTetEdges) {
      if (plane_sign(c[i]) * plane_sign(c[j]) < 0) split_point(c[i], c[j], -1, t);
    }
  }
}

// The polygon P cuts out of cut tet t, oriented out of its positive half.
std::vector<Index> TriangleInserter::section_polygon(Index t) {
  std::vector<std::pair<Index, Index>> sides;
  for (int k = 0; k < 4; ++k) {
    const auto f = mesh_.face_vertices(t, k);
    std::vector<Index> on_plane;
    for (int i = 0; i < 3; ++i) {
      const Index u = f[i];
      const Index v = f[(i + 1) % 3];
      if (plane_sign(u) == 0) on_plane.push_back(u);
      if (plane_sign(u) * plane_sign(v) < 0) on_plane.push_back(splits_.at(segment_key(u, v)));
    }
    if (on_plane.size() == 2) {
      sides.emplace_back(std::min(on_plane[0], on_plane[1]), std::max(on_plane[0], on_plane[1]));
    }
  }
  // An edge lying on P is the side of two faces.
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  std::vector<Index> cycle{sides.front().first, sides.front().second};
  sides.erase(sides.begin());
  while (!sides.empty()) {
    const auto next = std::find_if(sides.begin(), sides.end(), [&](const auto& s) {
      return s.first == cycle.back() || s.second == cycle.back();
    });
    if (next == sides.end()) throw RunError("triangle insertion: open section polygon (internal error)");
    const Index other = next->first == cycle.back() ? next->second : next->first;
    sides.erase(next);
    if (other != cycle.front()) cycle.push_back(other);
  }
  Index above = kNoVertex;
  for (Index v : mesh_.tet(t)) {
    if (plane_sign(v) > 0) above = v;
  }
  if (orient3d(mesh_.position(cycle[0]), mesh_.position(cycle[1]), mesh_.position(cycle[2]),
               mesh_.position(above)) > 0) {
    std::reverse(cycle.begin(), cycle.end());
  }
  return cycle;
}

// Splits a convex polygon by P (line < 0) or by a line through T's edge:
// (the part on the non-negative side, the part on the non-positive side);
// a part is empty when no corner is strictly on its side.
std::pair<std::vector<Index>, std::vector<Index>> TriangleInserter::split_polygon(
    const std::vector<Index>& polygon, int line, Index seed_tet) {
  const auto side = [&](Index v) { return line < 0 ? plane_sign(v) : line_side(line, v); };
  std::vector<int> sides(polygon.size());
  bool any_positive = false;
  bool any_negative = false;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    sides[i] = side(polygon[i]);
    any_positive |= sides[i] > 0;
    any_negative |= sides[i] < 0;
  }
  if (!any_negative) return {polygon, {}};
  if (!any_positive) return {{}, polygon};
  std::vector<Index> positive;
  std::vector<Index> negative;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const std::size_t j = (i + 1) % polygon.size();
    if (sides[i] >= 0) positive.push_back(polygon[i]);
    if (sides[i] <= 0) negative.push_back(polygon[i]);
    if (sides[i] * sides[j] < 0) {
      const Index w = split_point(polygon[i], polygon[j], line, seed_tet);
      positive.push_back(w);
      negative.push_back(w);
    }
  }
  return {positive, negative};
}

// The pieces of a polygon on P: those outside T keep `ids`, the one inside
// (if any) gets T's id too.
std::vector<TriangleInserter::Piece> TriangleInserter::clip_by_polygon(std::vector<Index> polygon,
                                                                       const Ids& ids, Index seed_tet) {
  std::vector<Piece> pieces;
  for (int line = 0; line < static_cast<int>(line_count()); ++line) {
    auto [inside, outside] = split_polygon(polygon, line, seed_tet);
    if (!outside.empty()) pieces.push_back({std::move(outside), ids});
    if (inside.empty()) return pieces;
    polygon = std::move(inside);
  }
  pieces.push_back({std::move(polygon), with_id(ids, id_)});
  return pieces;
}

void TriangleInserter::split_faces_of_cut_tets() {
  for (Index t : cut_tets_) {
    section_pieces_[t] = clip_by_polygon(section_polygon(t), {}, t);
    for (int k = 0; k < 4; ++k) {
      const auto f = mesh_.face_vertices(t, k);
      const int s0 = plane_sign(f[0]), s1 = plane_sign(f[1]), s2 = plane_sign(f[2]);
      const bool crossed = std::min({s0, s1, s2}) < 0 && std::max({s0, s1, s2}) > 0;
      if (!crossed || split_faces_.count(sorted_corners(f)) != 0) continue;
      const auto ids = mesh_.surface_ids(t, k);
      const Ids face_ids(ids.begin(), ids.end());
      auto [above, below] = split_polygon({f[0], f[1], f[2]}, -1, t);
      split_faces_[sorted_corners(f)] = {f, {{std::move(above), face_ids}, {std::move(below), face_ids}}};
    }
  }
}

// Existing faces lying on P that T overlaps: split along T's edges. A face
// that stays whole only gains T's id (both sides at once, no rebuild).
void TriangleInserter::clip_faces_on_plane() {
  for (Index t : candidates_) {
    if (stamped(cut_stamp_, t)) continue;
    for (int k = 0; k < 4; ++k) {
      const auto f = mesh_.face_vertices(t, k);
      if (plane_sign(f[0]) != 0 || plane_sign(f[1]) != 0 || plane_sign(f[2]) != 0) continue;
      if (split_faces_.count(sorted_corners(f)) != 0) continue;
      const std::array<HybridPoint, 3> face{mesh_.position(f[0]), mesh_.position(f[1]), mesh_.position(f[2])};
      if (!overlaps_polygon(face)) continue;
      const auto ids = mesh_.surface_ids(t, k);
      std::vector<Piece> pieces = clip_by_polygon({f[0], f[1], f[2]}, Ids(ids.begin(), ids.end()), t);
      if (pieces.size() == 1) {
        if (pieces.front().ids.size() != ids.size()) mesh_.set_surface_ids(t, k, pieces.front().ids);
        continue;
      }
      split_faces_[sorted_corners(f)] = {f, std::move(pieces)};
    }
  }
}

// The neighbour of t across the face containing edge (u, v) that does not
// lead back to `previous` (the first such face when previous is kNoTet and
// `first` is true, the second when it is false).
Index TriangleInserter::next_around_edge(Index t, Index u, Index v, Index previous, bool first) const {
  const Tet& c = mesh_.tet(t);
  bool skipped = false;
  for (int k = 0; k < 4; ++k) {
    if (c[k] == u || c[k] == v) continue;
    const Index n = mesh_.neighbour(t, k);
    if (previous != kNoTet) {
      if (n != previous) return n;
    } else if (first || skipped) {
      return n;
    } else {
      skipped = true;
    }
  }
  return kNoTet;
}

void TriangleInserter::add_to_cavity(Index t) {
  if (stamped(cavity_stamp_, t)) return;
  stamp(cavity_stamp_, t);
  cavity_.push_back(t);
}

// Every tet around edge (u, v): walk one way from `seed`, and the other way
// too when the hull (the box) stopped the first walk.
void TriangleInserter::walk_around_edge(Index u, Index v, Index seed) {
  add_to_cavity(seed);
  for (const bool first : {true, false}) {
    Index previous = seed;
    Index t = next_around_edge(seed, u, v, kNoTet, first);
    while (t != kNoTet && t != seed) {
      add_to_cavity(t);
      const Index next = next_around_edge(t, u, v, previous, true);
      previous = t;
      t = next;
    }
    if (t == seed) return;
  }
}

void TriangleInserter::collect_cavity() {
  for (Index t : cut_tets_) add_to_cavity(t);
  for (const auto& [u, v, seed] : split_mesh_edges_) walk_around_edge(u, v, seed);
  std::sort(cavity_.begin(), cavity_.end());
}

// ----------------------------------------------------------------- driver

bool TriangleInserter::insert(std::span<const Index> corners, std::uint32_t id) {
  if (!set_up_plane(corners, id)) {
    ++counters_.degenerate;
    return false;
  }
  if (mark_if_mesh_face()) {
    ++counters_.inserted;
    ++counters_.already_faces;
    return true;
  }
  collect_candidates();
  if (snap_distance_ > 0 && snap_points_near_plane() > 0) {
    forget_candidates();
    collect_candidates();
  }
  register_cut_points();
  split_faces_of_cut_tets();
  clip_faces_on_plane();
  collect_cavity();
  if (!cavity_.empty()) rebuild_cavity();
  if (settle_) settle_cut_points();
  ++counters_.inserted;
  return true;
}

}  // namespace mr::tetmesh::detail
