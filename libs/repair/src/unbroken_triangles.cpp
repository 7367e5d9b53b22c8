#include "unbroken_triangles.h"

#include <mr/core/grid_snap.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/spatial/improper_meetings.h>
#include <mr/spatial/triangle_distance.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <optional>
#include <span>
#include <unordered_map>

namespace mr::repair::detail {
namespace {

constexpr std::uint32_t kNone = ~std::uint32_t(0);
// Replacements that meet another face are taken back this many times
// before every replacement is given up.
constexpr int kValidationRounds = 4;
// How far the tiles' areas, projected on the triangle's plane, may differ
// from its own (rounded cut points); a fold or a gap is far larger.
constexpr double kAreaTolerance = 1e-6;

// Per peeled face, the input triangle nearest its centroid when all three
// of its corners are within `tolerance` of it; kNone otherwise.
std::vector<std::uint32_t> owners_of(const TriangleSoup& peeled, const TriangleSoup& input,
                                     double tolerance) {
  const spatial::AabbTree tree(input);
  std::vector<std::uint32_t> owners(peeled.triangles.size(), kNone);
  tbb::parallel_for(std::size_t(0), peeled.triangles.size(), [&](std::size_t f) {
    const std::array<Vec3d, 3> p = peeled.corners(f);
    const spatial::ClosestHit hit = tree.closest_within((p[0] + p[1] + p[2]) / 3.0, tolerance);
    if (!hit.found()) return;
    const std::array<Vec3d, 3> t = input.corners(hit.triangle);
    for (const Vec3d& q : p)
      if (spatial::squared_distance_to_triangle(q, t[0], t[1], t[2]) > tolerance * tolerance) return;
    owners[f] = hit.triangle;
  });
  return owners;
}

struct Group {
  std::uint32_t triangle = kNone;
  std::vector<Index> faces;
};

std::vector<Group> groups_by_owner(const std::vector<std::uint32_t>& owners) {
  std::vector<std::pair<std::uint32_t, Index>> owned;
  for (std::size_t f = 0; f < owners.size(); ++f)
    if (owners[f] != kNone) owned.emplace_back(owners[f], static_cast<Index>(f));
  std::sort(owned.begin(), owned.end());
  std::vector<Group> groups;
  for (const auto& [triangle, face] : owned) {
    if (groups.empty() || groups.back().triangle != triangle) groups.push_back({triangle, {}});
    groups.back().faces.push_back(face);
  }
  return groups;
}

// The boundary loop of `faces` when they form one oriented disk (every edge
// used once each way inside, one loop around, Euler characteristic 1), in
// the faces' orientation.
std::optional<std::vector<Index>> rim_of_disk(const TriangleSoup& surface, std::span<const Index> faces) {
  std::vector<std::pair<Index, Index>> halfedges;
  std::vector<Index> vertices;
  for (Index f : faces) {
    const Triangle& t = surface.triangles[f];
    for (int i = 0; i < 3; ++i) {
      halfedges.emplace_back(t[i], t[(i + 1) % 3]);
      vertices.push_back(t[i]);
    }
  }
  std::sort(halfedges.begin(), halfedges.end());
  if (std::adjacent_find(halfedges.begin(), halfedges.end()) != halfedges.end()) return std::nullopt;
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  std::vector<std::pair<Index, Index>> rim_edges;
  for (const auto& [a, b] : halfedges)
    if (!std::binary_search(halfedges.begin(), halfedges.end(), std::make_pair(b, a)))
      rim_edges.emplace_back(a, b);
  const std::size_t edges = rim_edges.size() + (halfedges.size() - rim_edges.size()) / 2;
  if (rim_edges.size() < 3 || vertices.size() + faces.size() != edges + 1) return std::nullopt;
  // rim_edges is sorted by its first vertex: one outgoing edge per rim vertex.
  for (std::size_t i = 1; i < rim_edges.size(); ++i)
    if (rim_edges[i].first == rim_edges[i - 1].first) return std::nullopt;
  std::vector<Index> rim{rim_edges.front().first};
  for (std::size_t step = 0; step < rim_edges.size(); ++step) {
    const auto next =
        std::lower_bound(rim_edges.begin(), rim_edges.end(), std::make_pair(rim.back(), Index(0)));
    if (next == rim_edges.end() || next->first != rim.back()) return std::nullopt;
    rim.push_back(next->second);
  }
  if (rim.back() != rim.front()) return std::nullopt;
  rim.pop_back();
  return rim;
}

// An input triangle tiled exactly by peeled faces.
struct Tiling {
  std::uint32_t triangle = kNone;
  std::vector<Index> faces;
  std::vector<Index> rim;  ///< in the faces' orientation, starting at a corner
  /// Where the triangle's corners are in `rim`: 0 < corner[1] < corner[2].
  std::array<std::size_t, 3> corner{};
};

bool within(const Vec3d& p, const Vec3d& a, const Vec3d& b, double tolerance) {
  return spatial::closest_on_segment(p, a, b).squared_distance <= tolerance * tolerance;
}

// Whether the faces' area, projected on the triangle's plane, is the
// triangle's, and none of them faces the other way (no fold).
bool covers_once(const TriangleSoup& surface, std::span<const Index> faces, const std::array<Vec3d, 3>& t) {
  const Vec3d normal = (t[1] - t[0]).cross(t[2] - t[0]);
  const double area = normal.norm();
  if (!(area > 0.0)) return false;
  const Vec3d unit = normal / area;
  double sum = 0.0, absolute = 0.0;
  for (Index f : faces) {
    const std::array<Vec3d, 3> p = surface.corners(f);
    const double projected = (p[1] - p[0]).cross(p[2] - p[0]).dot(unit);
    sum += projected;
    absolute += std::abs(projected);
  }
  return std::abs(std::abs(sum) - area) <= kAreaTolerance * area &&
         absolute - std::abs(sum) <= kAreaTolerance * area;
}

std::optional<Tiling> tiling_of(const TriangleSoup& peeled, const TriangleSoup& input, const Group& group,
                                double tolerance) {
  const std::array<Vec3d, 3> t = input.corners(group.triangle);
  if (!covers_once(peeled, group.faces, t)) return std::nullopt;
  std::optional<std::vector<Index>> rim = rim_of_disk(peeled, group.faces);
  if (!rim) return std::nullopt;
  std::array<std::size_t, 3> at{kNone, kNone, kNone};  // rim position of each input corner
  for (std::size_t i = 0; i < rim->size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (peeled.positions[(*rim)[i]] == t[c]) at[c] = i;
  if (std::find(at.begin(), at.end(), kNone) != at.end()) return std::nullopt;
  const std::size_t first = *std::min_element(at.begin(), at.end());
  std::rotate(rim->begin(), rim->begin() + static_cast<std::ptrdiff_t>(first), rim->end());
  for (std::size_t& i : at) i = (i + rim->size() - first) % rim->size();
  std::sort(at.begin(), at.end());
  // Every rim vertex between two corners lies on the edge joining them.
  for (int side = 0; side < 3; ++side) {
    const std::size_t from = at[side], to = side == 2 ? rim->size() : at[side + 1];
    const Vec3d& a = peeled.positions[(*rim)[from]];
    const Vec3d& b = peeled.positions[(*rim)[to % rim->size()]];
    for (std::size_t i = from + 1; i < to; ++i)
      if (!within(peeled.positions[(*rim)[i]], a, b, tolerance)) return std::nullopt;
  }
  return Tiling{group.triangle, group.faces, std::move(*rim), at};
}

std::vector<Tiling> tilings_of(const TriangleSoup& peeled, const TriangleSoup& input,
                               const std::vector<Group>& groups, double tolerance) {
  std::vector<std::optional<Tiling>> found(groups.size());
  tbb::parallel_for(std::size_t(0), groups.size(),
                    [&](std::size_t g) { found[g] = tiling_of(peeled, input, groups[g], tolerance); });
  std::vector<Tiling> tilings;
  for (std::optional<Tiling>& t : found)
    if (t) tilings.push_back(std::move(*t));
  return tilings;
}

struct PositionHash {
  std::size_t operator()(const Vec3d& p) const {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) h = h * 0x9E3779B97F4A7C15ull + std::bit_cast<std::uint64_t>(p[k] + 0.0);
    return h ^ (h >> 29);
  }
};

// Snapped position -> the input position it came from; NaN where several did.
using Unsnapping = std::unordered_map<Vec3d, Vec3d, PositionHash>;

Unsnapping unsnapping(const TriangleSoup& input, double snap_spacing) {
  TriangleSoup snapped;
  snapped.positions = input.positions;
  if (snap_spacing > 0.0) snap_to_grid(snapped, snap_spacing);
  Unsnapping map;
  for (std::size_t i = 0; i < input.positions.size(); ++i) {
    const auto [it, added] = map.emplace(snapped.positions[i], input.positions[i]);
    if (!added && it->second != input.positions[i]) it->second = Vec3d::Constant(std::nan(""));
  }
  return map;
}

class Assembly {
 public:
  Assembly(const TriangleSoup& peeled, const std::vector<Tiling>& tilings, const Unsnapping& unsnapping)
      : peeled_(peeled),
        tilings_(tilings),
        unsnapping_(unsnapping),
        active_(tilings.size(), 1),
        keep_snapped_(peeled.positions.size(), 0),
        tiling_of_face_(peeled.triangles.size(), kNone) {
    for (std::size_t k = 0; k < tilings.size(); ++k)
      for (Index f : tilings[k].faces) tiling_of_face_[f] = static_cast<std::uint32_t>(k);
  }

  void deactivate(std::size_t tiling) { active_[tiling] = 0; }
  void deactivate_all() { std::fill(active_.begin(), active_.end(), std::uint8_t(0)); }
  void keep_snapped(Index vertex) { keep_snapped_[vertex] = 1; }

  /// What changed against the peeled surface: per face, the tiling that
  /// made it (kNone: a peeled face); per vertex, whether it went back to
  /// the input's coordinates.
  struct Changes {
    std::vector<std::uint32_t> made_by;
    std::vector<std::uint8_t> restored;
  };

  /// The surface with every active tiling replaced.
  UnbrokenTriangles build(Changes& changes) const {
    UnbrokenTriangles out;
    out.surface.positions = peeled_.positions;
    std::vector<std::uint32_t>& made_by = changes.made_by;
    made_by.clear();
    const std::vector<std::uint8_t> needed = needed_vertices();
    for (std::size_t f = 0; f < peeled_.triangles.size(); ++f)
      if (!active_at(f)) {
        out.surface.triangles.push_back(peeled_.triangles[f]);
        out.origins.push_back(FaceOrigin::peeled);
        made_by.push_back(kNone);
      }
    for (std::size_t k = 0; k < tilings_.size(); ++k)
      if (active_[k]) {
        const std::size_t before = out.surface.triangles.size();
        emit(tilings_[k], needed, out);
        made_by.resize(out.surface.triangles.size(), static_cast<std::uint32_t>(k));
        const bool whole = out.surface.triangles.size() - before == 1;
        out.origins.resize(out.surface.triangles.size(), whole ? FaceOrigin::unbroken : FaceOrigin::fanned);
        ++out.put_back;
      }
    changes.restored = restore_corners(out.surface);
    return out;
  }

 private:
  bool active_at(std::size_t face) const {
    return tiling_of_face_[face] != kNone && active_[tiling_of_face_[face]];
  }

  // The corners of put-back triangles go back to the input's coordinates
  // (the faces around them move by less than the snapping grid's step, and
  // are checked), unless two input positions snapped to one.
  std::vector<std::uint8_t> restore_corners(TriangleSoup& surface) const {
    std::vector<std::uint8_t> restored(surface.positions.size(), 0);
    for (std::size_t k = 0; k < tilings_.size(); ++k)
      if (active_[k])
        for (std::size_t c : tilings_[k].corner) {
          const Index v = tilings_[k].rim[c];
          if (keep_snapped_[v] || restored[v]) continue;
          const auto it = unsnapping_.find(peeled_.positions[v]);
          if (it == unsnapping_.end() || std::isnan(it->second.x()) || it->second == peeled_.positions[v])
            continue;
          surface.positions[v] = it->second;
          restored[v] = 1;
        }
    return restored;
  }

  // Vertices a replaced triangle must keep on its edges: those of faces
  // that stay as peeled, and the corners of every replaced triangle.
  std::vector<std::uint8_t> needed_vertices() const {
    std::vector<std::uint8_t> needed(peeled_.positions.size(), 0);
    for (std::size_t f = 0; f < peeled_.triangles.size(); ++f)
      if (!active_at(f))
        for (Index v : peeled_.triangles[f]) needed[v] = 1;
    for (std::size_t k = 0; k < tilings_.size(); ++k)
      if (active_[k])
        for (std::size_t c : tilings_[k].corner) needed[tilings_[k].rim[c]] = 1;
    return needed;
  }

  // The triangle with the needed rim points: itself, a fan from the corner
  // facing the only edge with points, or a fan from its centroid.
  void emit(const Tiling& tiling, const std::vector<std::uint8_t>& needed, UnbrokenTriangles& out) const {
    std::vector<Index> polygon;
    std::array<int, 3> points_on_side{};
    const auto corner_vertex = [&](std::size_t c) { return tiling.rim[tiling.corner[c % 3]]; };
    for (std::size_t i = 0, side = 0; i < tiling.rim.size(); ++i) {
      if (side < 2 && i == tiling.corner[side + 1]) ++side;
      const bool corner = i == tiling.corner[side];
      if (!corner && !needed[tiling.rim[i]]) continue;
      polygon.push_back(tiling.rim[i]);
      if (corner) continue;
      ++points_on_side[side];
      out.fan_merges.push_back({tiling.rim[i], corner_vertex(side)});
      out.fan_merges.push_back({tiling.rim[i], corner_vertex(side + 1)});
    }
    auto& triangles = out.surface.triangles;
    if (polygon.size() == 3) {
      triangles.push_back({polygon[0], polygon[1], polygon[2]});
      return;
    }
    const auto has_points = [](int n) { return n > 0; };
    if (std::count_if(points_on_side.begin(), points_on_side.end(), has_points) == 1) {
      const auto side =
          std::find_if(points_on_side.begin(), points_on_side.end(), has_points) - points_on_side.begin();
      // The corner facing the side with points: the one that does not bound it.
      const Index apex = tiling.rim[tiling.corner[(side + 2) % 3]];
      fan(polygon,
          static_cast<std::size_t>(std::find(polygon.begin(), polygon.end(), apex) - polygon.begin()),
          triangles);
      return;
    }
    const Index centroid = static_cast<Index>(out.surface.positions.size());
    const Vec3d& a = peeled_.positions[tiling.rim[tiling.corner[0]]];
    const Vec3d& b = peeled_.positions[tiling.rim[tiling.corner[1]]];
    const Vec3d& c = peeled_.positions[tiling.rim[tiling.corner[2]]];
    out.surface.positions.push_back((a + b + c) / 3.0);
    for (std::size_t k = 0; k < 3; ++k) out.fan_merges.push_back({centroid, corner_vertex(k)});
    for (std::size_t i = 0; i < polygon.size(); ++i)
      triangles.push_back({centroid, polygon[i], polygon[(i + 1) % polygon.size()]});
  }

  static void fan(const std::vector<Index>& polygon, std::size_t apex, std::vector<Triangle>& triangles) {
    const std::size_t n = polygon.size();
    for (std::size_t i = 1; i + 1 < n; ++i)
      triangles.push_back({polygon[apex], polygon[(apex + i) % n], polygon[(apex + i + 1) % n]});
  }

  const TriangleSoup& peeled_;
  const std::vector<Tiling>& tilings_;
  const Unsnapping& unsnapping_;
  std::vector<std::uint8_t> active_;
  std::vector<std::uint8_t> keep_snapped_;  // per vertex: its restoration made a face meet another
  std::vector<std::uint32_t> tiling_of_face_;
};

// The changed faces (made by a tiling, or around a restored vertex) that
// meet another face improperly (exact).
std::vector<Index> conflicting_faces(const TriangleSoup& surface, const Assembly::Changes& changes) {
  std::vector<std::uint8_t> changed(surface.triangles.size(), 0);
  for (std::size_t f = 0; f < changed.size(); ++f) {
    const Triangle& t = surface.triangles[f];
    changed[f] = changes.made_by[f] != kNone || changes.restored[t[0]] || changes.restored[t[1]] ||
                 changes.restored[t[2]];
  }
  const std::vector<std::uint8_t> meets = spatial::faces_meeting_others(surface, changed);
  std::vector<Index> faces;
  for (std::size_t f = 0; f < meets.size(); ++f)
    if (meets[f]) faces.push_back(static_cast<Index>(f));
  return faces;
}

// Drops the vertices no face uses, renumbering the fan merges' vertices
// (all used: the fans' own).
void drop_unused_vertices(UnbrokenTriangles& out) {
  TriangleSoup& surface = out.surface;
  std::vector<Index> new_index(surface.positions.size(), kNone);
  std::vector<Vec3d> positions;
  for (Triangle& t : surface.triangles)
    for (Index& v : t) {
      if (new_index[v] == kNone) {
        new_index[v] = static_cast<Index>(positions.size());
        positions.push_back(surface.positions[v]);
      }
      v = new_index[v];
    }
  surface.positions = std::move(positions);
  for (std::array<Index, 2>& merge : out.fan_merges)
    for (Index& v : merge) v = new_index[v];
}

}  // namespace

UnbrokenTriangles put_back_unbroken_triangles(const TriangleSoup& peeled, const TriangleSoup& inserted,
                                              const TriangleSoup& input, double snap_spacing,
                                              double tolerance) {
  const std::vector<Tiling> tilings =
      tilings_of(peeled, inserted, groups_by_owner(owners_of(peeled, inserted, tolerance)), tolerance);
  const Unsnapping map = unsnapping(input, snap_spacing);
  Assembly assembly(peeled, tilings, map);
  Assembly::Changes changes;
  UnbrokenTriangles out = assembly.build(changes);
  for (int round = 0;; ++round) {
    const std::vector<Index> conflicts = conflicting_faces(out.surface, changes);
    if (conflicts.empty()) break;
    if (round == kValidationRounds) {
      assembly.deactivate_all();
    } else {
      for (Index f : conflicts) {
        if (changes.made_by[f] != kNone) assembly.deactivate(changes.made_by[f]);
        for (Index v : out.surface.triangles[f])
          if (changes.restored[v]) assembly.keep_snapped(v);
      }
    }
    out = assembly.build(changes);
  }
  drop_unused_vertices(out);
  return out;
}

}  // namespace mr::repair::detail
