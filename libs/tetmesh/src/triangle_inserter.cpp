#include "triangle_inserter.h"

#include "inserter_keys.h"

#include <mr/core/errors.h>
#include <mr/kernel/constructions.h>
#include <mr/kernel/point_box.h>
#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <optional>

namespace mr::tetmesh::detail {
namespace {

constexpr std::array<std::array<int, 2>, 6> kTetEdges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

std::vector<std::uint32_t> with_id(std::vector<std::uint32_t> ids, std::uint32_t id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
    ids.insert(std::upper_bound(ids.begin(), ids.end(), id), id);
  }
  return ids;
}

// Whether the convex polygon `polygon` (on P, any order) overlaps the
// interior of the convex polygon `convex` (T), by separating lines: T's edge lines, and the
// polygon's own edges (a pair of corners with all other corners on one
// side). side(p, q, x) is orient2d of the projections, or kUncertainSign
// from a filter; nullopt when an uncertain sign would decide.
template <class Point, class Side>
std::optional<bool> polygon_overlaps_convex(std::span<const Point> polygon, std::span<const Point> convex,
                                            int orientation, Side side) {
  for (std::size_t line = 0; line < convex.size(); ++line) {
    const Point& p = convex[line];
    const Point& q = convex[(line + 1) % convex.size()];
    bool uncertain = false;
    bool some_inside = false;
    for (const Point& x : polygon) {
      const int s = side(p, q, x);
      if (s == kUncertainSign) {
        uncertain = true;
      } else if (orientation * s > 0) {
        some_inside = true;
        break;
      }
    }
    if (some_inside) continue;
    if (uncertain) return std::nullopt;
    return false;  // every corner on or outside this edge line
  }
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    for (std::size_t j = i + 1; j < polygon.size(); ++j) {
      int polygon_side = 0;
      bool is_edge = true;
      for (std::size_t k = 0; k < polygon.size() && is_edge; ++k) {
        if (k == i || k == j) continue;
        const int s = side(polygon[i], polygon[j], polygon[k]);
        if (s == kUncertainSign) return std::nullopt;
        if (s != 0 && polygon_side != 0 && s != polygon_side) is_edge = false;
        if (s != 0) polygon_side = s;
      }
      if (!is_edge || polygon_side == 0) continue;
      bool separated = true;
      bool uncertain = false;
      for (const Point& corner : convex) {
        const int s = side(polygon[i], polygon[j], corner);
        if (s == kUncertainSign) {
          uncertain = true;
        } else if (s * polygon_side > 0) {
          separated = false;
        }
      }
      if (!separated) continue;
      if (uncertain) return std::nullopt;
      return false;
    }
  }
  return true;
}

}  // namespace

TriangleInserter::TriangleInserter(Mesh& mesh, std::size_t max_exact_bits)
    : mesh_(mesh), max_exact_bits_(max_exact_bits) {
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

// ---------------------------------------------------------------- the plane

bool TriangleInserter::set_up_plane(std::span<const Index> corners, std::uint32_t id) {
  if (corners.size() < 3 || corners.size() > kMaxCorners) {
    throw RunError("triangle insertion: a polygon needs 3 to 12 corners (internal error)");
  }
  const Index a = corners[0], b = corners[1], c = corners[2];
  if (a == b || b == c || c == a) return false;
  const HybridPoint& pa = mesh_.position(a);
  const HybridPoint& pb = mesh_.position(b);
  const HybridPoint& pc = mesh_.position(c);
  if (collinear(pa, pb, pc)) return false;
  ++generation_;
  id_ = id;
  corners_.assign(corners.begin(), corners.end());
  // Project along the axis where T is widest: its projection is then not
  // degenerate, and the lines through its edges are the vertical planes
  // through them.
  const Vec3d normal = (pb.approx - pa.approx).cross(pc.approx - pa.approx);
  normal.cwiseAbs().maxCoeff(&axis_);
  orientation_ = orient2d_projected(pa, pb, pc, axis_);
  if (orientation_ == 0) {  // the double normal chose a degenerate projection: take any other
    for (int k = 0; k < 3 && orientation_ == 0; ++k) {
      axis_ = k;
      orientation_ = orient2d_projected(pa, pb, pc, k);
    }
  }
  line_lift_.clear();
  for (const Index corner : corners_) {
    ExactPoint3 lifted = mesh_.position(corner).to_exact();
    (axis_ == 0 ? lifted.x : axis_ == 1 ? lifted.y : lifted.z) += 1;
    line_lift_.push_back(HybridPoint::from_exact(std::move(lifted)));
  }
  plane_sign_.clear();
  line_side_.clear();
  candidates_.clear();
  cut_tets_.clear();
  cavity_.clear();
  splits_.clear();
  plane_points_.clear();
  split_mesh_edges_.clear();
  new_vertices_.clear();
  section_pieces_.clear();
  split_faces_.clear();
  ids_storage_.clear();
  return true;
}

int TriangleInserter::plane_sign(Index v) {
  if (new_vertices_.count(v) != 0) return 0;  // cut points lie on P exactly
  const auto [it, inserted] = plane_sign_.try_emplace(v, 0);
  if (inserted) {
    it->second = orient3d(mesh_.position(corners_[0]), mesh_.position(corners_[1]),
                          mesh_.position(corners_[2]), mesh_.position(v));
  }
  return it->second;
}

int TriangleInserter::line_side(int line, Index v) {
  auto [it, inserted] = line_side_.try_emplace(v);
  if (inserted) it->second.fill(2);
  std::int8_t& side = it->second[line];
  if (side == 2) {
    const Index p = corners_[line];
    const Index q = corners_[(line + 1) % line_count()];
    side = static_cast<std::int8_t>(
        orientation_ * orient2d_projected(mesh_.position(p), mesh_.position(q), mesh_.position(v), axis_));
  }
  return side;
}

// ---------------------------------------------------------- candidate tets

// Conservative: false only when the tet cannot meet T (strictly on one side
// of P, or strictly outside one of the lines through T's edges).
bool TriangleInserter::may_meet_polygon(Index t) {
  const Tet& c = mesh_.tet(t);
  int above = 0;
  int below = 0;
  for (Index v : c) {
    const int s = plane_sign(v);
    above += s > 0;
    below += s < 0;
  }
  if (above == 4 || below == 4) return false;
  for (int line = 0; line < static_cast<int>(line_count()); ++line) {
    int outside = 0;
    for (Index v : c) outside += line_side(line, v) < 0;
    if (outside == 4) return false;
  }
  return true;
}

void TriangleInserter::collect_candidates() {
  Index start = seed_tet_[corners_[0]];
  if (start == kNoTet || !mesh_.tet_alive(start) || mesh_.corner_of(start, corners_[0]) < 0) {
    throw RunError("triangle insertion: lost the tets around an input vertex (internal error)");
  }
  std::vector<Index> queue{start};
  stamp(candidate_stamp_, start);
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const Index t = queue[i];
    if (!may_meet_polygon(t)) continue;
    candidates_.push_back(t);
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh_.neighbour(t, k);
      if (n == kNoTet || stamped(candidate_stamp_, n)) continue;
      stamp(candidate_stamp_, n);
      queue.push_back(n);
    }
  }
  std::sort(candidates_.begin(), candidates_.end());
  for (Index t : candidates_) {
    if (is_cut(t)) {
      cut_tets_.push_back(t);
      stamp(cut_stamp_, t);
    }
  }
}

// P crosses t and the section overlaps T: only then must t be cut (a tet
// whose interior meets T has a section overlapping T with positive area).
bool TriangleInserter::is_cut(Index t) {
  bool above = false;
  bool below = false;
  for (Index v : mesh_.tet(t)) {
    const int s = plane_sign(v);
    above |= s > 0;
    below |= s < 0;
  }
  if (!above || !below) return false;
  if (section_outside_a_line(t)) return false;
  const Tet& c = mesh_.tet(t);
  if (const std::optional<bool> overlaps = section_overlaps_filtered(c)) return *overlaps;
  std::vector<HybridPoint> section;
  for (int i = 0; i < 4; ++i) {
    if (plane_sign(c[i]) == 0) section.push_back(mesh_.position(c[i]));
  }
  for (const auto& [i, j] : kTetEdges) {
    if (plane_sign(c[i]) * plane_sign(c[j]) < 0) section.push_back(plane_point(c[i], c[j]));
  }
  return overlaps_polygon(section);
}

// A cheap exact pre-test on the corners' sides only: the section lies
// strictly outside line j when its corners on P do and both ends of every
// crossed edge do (a cut point is between its edge's ends).
bool TriangleInserter::section_outside_a_line(Index t) {
  const Tet& c = mesh_.tet(t);
  for (int line = 0; line < static_cast<int>(line_count()); ++line) {
    bool outside = true;
    for (int i = 0; i < 4 && outside; ++i) {
      if (plane_sign(c[i]) == 0 && line_side(line, c[i]) >= 0) outside = false;
    }
    for (const auto& [i, j] : kTetEdges) {
      if (!outside) break;
      if (plane_sign(c[i]) * plane_sign(c[j]) < 0 &&
          (line_side(line, c[i]) >= 0 || line_side(line, c[j]) >= 0)) {
        outside = false;
      }
    }
    if (outside) return true;
  }
  return false;
}

const HybridPoint& TriangleInserter::plane_point(Index u, Index v) {
  const auto [it, inserted] = plane_points_.try_emplace(segment_key(u, v));
  if (inserted) {
    it->second = HybridPoint::from_exact(
        intersect_segment_plane(mesh_.position(u), mesh_.position(v), mesh_.position(corners_[0]),
                                mesh_.position(corners_[1]), mesh_.position(corners_[2])));
  }
  return it->second;
}

// The section-overlap test of is_cut on boxes around the section's corners
// (interval arithmetic): most tets are decided without constructing their
// cut points exactly, which used to take most of the insertion time.
std::optional<bool> TriangleInserter::section_overlaps_filtered(const Tet& c) {
  std::array<PointBox, 4> section;  // a plane meets a tet in at most 4 points
  std::size_t count = 0;
  for (int i = 0; i < 4; ++i) {
    if (plane_sign(c[i]) == 0) section[count++] = box_of(mesh_.position(c[i]));
  }
  for (const auto& [i, j] : kTetEdges) {
    if (plane_sign(c[i]) * plane_sign(c[j]) >= 0) continue;
    if (count == section.size()) return std::nullopt;
    const auto known = plane_points_.find(segment_key(c[i], c[j]));
    if (known != plane_points_.end()) {
      section[count++] = box_of(known->second);
      continue;
    }
    const std::optional<PointBox> box =
        box_of_segment_plane(mesh_.position(c[i]), mesh_.position(c[j]), mesh_.position(corners_[0]),
                             mesh_.position(corners_[1]), mesh_.position(corners_[2]));
    if (!box) return std::nullopt;
    section[count++] = *box;
  }
  std::array<PointBox, kMaxCorners> polygon;
  for (std::size_t i = 0; i < line_count(); ++i) polygon[i] = box_of(mesh_.position(corners_[i]));
  return polygon_overlaps_convex(std::span<const PointBox>(section.data(), count),
                                 std::span<const PointBox>(polygon.data(), line_count()), orientation_,
                                 [&](const PointBox& p, const PointBox& q, const PointBox& x) {
                                   return orient2d_projected(p, q, x, axis_);
                                 });
}

// Whether the convex polygon with corners `points` (on P, any order)
// overlaps T's interior (exact).
bool TriangleInserter::overlaps_polygon(std::span<const HybridPoint> points) {
  std::vector<HybridPoint> polygon;
  polygon.reserve(line_count());
  for (const Index corner : corners_) polygon.push_back(mesh_.position(corner));
  return *polygon_overlaps_convex(points, std::span<const HybridPoint>(polygon), orientation_,
                                  [&](const HybridPoint& p, const HybridPoint& q, const HybridPoint& x) {
                                    return orient2d_projected(p, q, x, axis_);
                                  });
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

// A triangle that is a face of the mesh already needs no cut: no tet of a
// tetrahedralization crosses one of its faces, and no point lies inside it.
// Marking it is the whole insertion, found in the star of one corner instead
// of by the candidate walk (which visits over a thousand tets per triangle
// on a scan, whose Delaunay background has most input triangles as faces).
bool TriangleInserter::mark_if_mesh_face() {
  if (corners_.size() != 3) return false;
  const Index a = corners_[0], b = corners_[1], c = corners_[2];
  const Index seed = seed_tet_[a];
  if (seed == kNoTet || !mesh_.tet_alive(seed) || mesh_.corner_of(seed, a) < 0) return false;
  for (const Index t : tets_around_vertex(mesh_, a, seed)) {
    const int corner_b = mesh_.corner_of(t, b), corner_c = mesh_.corner_of(t, c);
    if (corner_b < 0 || corner_c < 0) continue;
    const int face = 6 - mesh_.corner_of(t, a) - corner_b - corner_c;  // the corner that is none of the three
    const auto ids = mesh_.surface_ids(t, face);
    mesh_.set_surface_ids(t, face, with_id(Ids(ids.begin(), ids.end()), id_));
    return true;
  }
  return false;
}

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
  register_cut_points();
  split_faces_of_cut_tets();
  clip_faces_on_plane();
  collect_cavity();
  if (!cavity_.empty()) rebuild_cavity();
  ++counters_.inserted;
  return true;
}

}  // namespace mr::tetmesh::detail
