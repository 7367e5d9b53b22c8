// Stage 4, first half: where the polygon's plane lies (see
// triangle_inserter.h): the plane and its lines, the candidate walk, which
// tets the plane cuts and whether their section overlaps the polygon, and
// the fast path for a triangle that is a mesh face already.

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

TriangleInserter::VertexSides& TriangleInserter::sides_of(Index v) {
  if (sides_.size() <= v) sides_.resize(std::max<std::size_t>(v + 1, mesh_.vertex_slots()));
  VertexSides& sides = sides_[v];
  if (sides.stamp != generation_) {
    sides.stamp = generation_;
    sides.plane = 2;
    sides.lines.fill(2);
  }
  return sides;
}

int TriangleInserter::plane_sign(Index v) {
  if (new_vertices_.count(v) != 0) return 0;  // cut points lie on P exactly
  std::int8_t& sign = sides_of(v).plane;
  if (sign == 2) {
    sign = static_cast<std::int8_t>(orient3d(mesh_.position(corners_[0]), mesh_.position(corners_[1]),
                                             mesh_.position(corners_[2]), mesh_.position(v)));
  }
  return sign;
}

int TriangleInserter::line_side(int line, Index v) {
  std::int8_t& side = sides_of(v).lines[static_cast<std::size_t>(line)];
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

// ---------------------------------------------------------- a face already

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
}  // namespace mr::tetmesh::detail
