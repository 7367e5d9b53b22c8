#include <mr/repair/round_to_grid.h>

#include "surface_breaks.h"

#include <mr/core/errors.h>
#include <mr/kernel/intersections.h>
#include <mr/kernel/predicates.h>
#include <mr/spatial/box_grid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <span>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace mr::repair {
namespace {

struct Box {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d hi = Vec3d::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool overlaps(const Box& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
};

// Faces around each vertex (mutable: a collapse moves faces to another vertex).
using Incidence = std::vector<std::vector<Index>>;

Incidence incidence_of(const TriangleSoup& surface) {
  Incidence incidence(surface.positions.size());
  for (std::size_t f = 0; f < surface.triangles.size(); ++f)
    for (Index v : surface.triangles[f]) incidence[v].push_back(static_cast<Index>(f));
  return incidence;
}

class VertexPlacement {
 public:
  static constexpr Index kNoFace = std::numeric_limits<Index>::max();

  VertexPlacement(TriangleSoup& surface, const CoordinateGrid& grid, const GridRoundingOptions& options)
      : surface_(surface),
        grid_(grid),
        options_(options),
        original_(surface.positions),
        incidence_(incidence_of(surface)),
        on_grid_(surface.positions.size(), 0),
        collapsed_(surface.positions.size(), 0),
        removed_(surface.triangles.size(), 0),
        last_refusal_(surface.positions.size(), kNoFace) {
    for (std::size_t v = 0; v < original_.size(); ++v) occupied_.emplace(original_[v], static_cast<Index>(v));
    build_reach();
  }

  GridRoundingStats run() {
    GridRoundingStats stats;
    stats.vertices = original_.size();
    for (std::size_t v = 0; v < original_.size(); ++v) {
      if (grid_.holds(original_[v]))
        on_grid_[v] = 1;
      else
        ++stats.moved;
    }
    place_nearest_at_once(stats);
    std::vector<Index> left = unplaced();
    // Where no grid point around a vertex works (sheets closer than a grid
    // step all around it), the vertex goes: collapsed onto a neighbour,
    // which is then placed (again) with the others left.
    for (int round = 0; !left.empty() && round < kCollapseRounds; ++round) {
      left = place_all(left, round > 0, stats);
      bool changed = false;
      for (Index v : left)
        if (!on_grid_[v] && release_neighbours(v)) {
          changed = true;
          place(v, true, stats);  // first, while its neighbours are back where they were
        }
      for (Index v : left)
        if (!on_grid_[v] && collapse_onto_neighbour(v)) ++stats.collapsed, changed = true;
      if (!changed) break;
      left = unplaced();
    }
    stats.tries = tries_;
    if (stats.collapsed > 0) remove_collapsed();
    if (!left.empty())
      throw RunError("cannot place " + std::to_string(left.size()) + " vertices on the " + grid_.name() +
                     " grid of the output without a self-intersection, a degenerate face or two vertices on "
                     "one point (searched " +
                     std::to_string(options_.max_steps * options_.max_stride) + " grid steps around each)");
    return stats;
  }

 private:
  static constexpr int kCollapseRounds = 8;
  static constexpr int kAtOnceRounds = 8;

  // Every vertex off the grid goes to its nearest grid point at once; one
  // exact check of the whole surface (parallel) finds the faces that then
  // meet another improperly or lose their plane, and the vertices that land
  // on another; their moved corners go back, and the check runs again until
  // it finds nothing. Only the vertices sent back are placed one at a time
  // (place_all), each checked against the faces near it: on CAD models
  // every vertex has thousands (long slivers, fans), so one vertex at a
  // time was most of the stage.
  void place_nearest_at_once(GridRoundingStats& stats) {
    std::vector<std::uint8_t> tentative(original_.size(), 0);
    std::vector<Index> moved;
    for (std::size_t v = 0; v < original_.size(); ++v) {
      if (on_grid_[v]) continue;
      const Vec3d nearest = grid_.nearest(original_[v]);
      if (!grid_.holds(nearest)) continue;
      count_try();
      surface_.positions[v] = nearest;
      tentative[v] = 1;
      moved.push_back(static_cast<Index>(v));
    }
    for (int round = 0; !moved.empty(); ++round) {
      const std::vector<std::uint8_t> back =
          round < kAtOnceRounds ? vertices_breaking_surface(surface_, tentative) : tentative;
      const auto goes_back = [&](Index v) { return back[v] != 0; };
      if (std::none_of(moved.begin(), moved.end(), goes_back)) break;
      for (Index v : moved)
        if (goes_back(v)) surface_.positions[v] = original_[v], tentative[v] = 0, ++stats.sent_back;
      std::erase_if(moved, goes_back);
    }
    for (Index v : moved) {
      if (auto it = occupied_.find(original_[v]); it != occupied_.end() && it->second == v)
        occupied_.erase(it);
      occupied_[surface_.positions[v]] = v;
      on_grid_[v] = 1;
      stats.max_move = std::max(stats.max_move, (surface_.positions[v] - original_[v]).norm());
    }
  }

  // Sweeps over `left` until every vertex is placed, a searching sweep
  // places none, or the passes run out; the first sweep of a run tries the
  // nearest grid point only, so that a vertex refused because a neighbour
  // has not moved yet is tried again after it did. Returns the unplaced.
  std::vector<Index> place_all(std::vector<Index> left, bool search, GridRoundingStats& stats) {
    for (int pass = 0; !left.empty() && pass < options_.max_passes; ++pass, search = true) {
      ++stats.passes;
      for (Index v : left) place(v, search, stats);
      const std::vector<Index> still = unplaced();
      if (search && still.size() == left.size()) return still;
      left = still;
    }
    return left;
  }

  std::vector<Index> unplaced() const {
    std::vector<Index> out;
    for (std::size_t v = 0; v < on_grid_.size(); ++v)
      if (!on_grid_[v]) out.push_back(static_cast<Index>(v));
    return out;
  }

  // Moves v's placed neighbours back to their original positions where that
  // keeps the surface valid and marks them unplaced, so that v is placed
  // before them (they were rounded first and left v no room). True if any moved.
  bool release_neighbours(Index v) {
    bool any = false;
    for (Index w : neighbours(v)) {
      if (!on_grid_[w] || grid_.holds(original_[w]) || collapsed_[w]) continue;
      const std::vector<Index> nearby = faces_near(w);
      forget_refusal_unless_near(w, nearby);
      if (try_position(w, original_[w], nearby)) {
        on_grid_[w] = 0;
        any = true;
      }
    }
    return any;
  }

  // The vertices sharing a face with v, sorted, without v.
  std::vector<Index> neighbours(Index v) const {
    std::vector<Index> out;
    for (Index f : faces_around(v))
      for (Index w : surface_.triangles[f])
        if (w != v) out.push_back(w);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Collapses the edge v-w into w's (grid) position if the surface stays a
  // valid one, exactly: the link condition (v and w share no neighbour but
  // the two faces on their edge), no face degenerate, repeated or meeting
  // another improperly. Tries the neighbours nearest to v first; one not
  // yet on the grid is placed afterwards.
  bool collapse_onto_neighbour(Index v) {
    std::vector<Index> candidates = neighbours(v);
    std::stable_sort(candidates.begin(), candidates.end(), [&](Index a, Index b) {
      return (surface_.positions[a] - original_[v]).squaredNorm() <
             (surface_.positions[b] - original_[v]).squaredNorm();
    });
    for (Index w : candidates)
      if (try_collapse(v, w)) return true;
    return false;
  }

  bool try_collapse(Index v, Index w) {
    std::vector<Index> shared, kept;  // faces on edge v-w, the other faces of v
    for (Index f : faces_around(v)) {
      const Triangle& t = surface_.triangles[f];
      (std::find(t.begin(), t.end(), w) != t.end() ? shared : kept).push_back(f);
    }
    if (shared.size() != 2) return false;
    std::vector<Index> common, nv = neighbours(v), nw = neighbours(w);
    std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
    if (common.size() != 2) return false;  // the link condition
    std::vector<std::array<Vec3d, 3>> moved;
    for (Index f : kept) {
      moved.push_back(corners(f, v, surface_.positions[w]));
      const auto& m = moved.back();
      if (collinear(m[0], m[1], m[2])) return false;
    }
    // Faces near the collapse: near v or w, minus those that go or move.
    std::vector<Index> nearby = faces_near(v);
    for (Index g : faces_around(w))
      if (std::find(shared.begin(), shared.end(), g) == shared.end()) nearby.push_back(g);
    std::sort(nearby.begin(), nearby.end());
    nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
    const auto improper = [](const std::array<Vec3d, 3>& a, const std::array<Vec3d, 3>& b) {
      return intersect_triangles(a[0], a[1], a[2], b[0], b[1], b[2]).improper();
    };
    for (std::size_t i = 0; i < moved.size(); ++i) {
      for (std::size_t j = i + 1; j < moved.size(); ++j)
        if (improper(moved[i], moved[j])) return false;
      for (Index g : nearby) {
        if (removed_[g] || std::find(shared.begin(), shared.end(), g) != shared.end()) continue;
        const Triangle& t = surface_.triangles[g];
        const std::array<Vec3d, 3> other{surface_.positions[t[0]], surface_.positions[t[1]],
                                         surface_.positions[t[2]]};
        if (improper(moved[i], other)) return false;
      }
    }
    apply_collapse(v, w, shared, kept);
    return true;
  }

  void apply_collapse(Index v, Index w, const std::vector<Index>& shared, const std::vector<Index>& kept) {
    for (Index f : shared) {
      removed_[f] = 1;
      faces_.erase(f);
      for (Index u : surface_.triangles[f])
        if (u != v) std::erase(incidence_[u], f);
    }
    for (Index f : kept) {
      for (Index& u : surface_.triangles[f])
        if (u == v) u = w;
      incidence_[w].push_back(f);
      face_reach_[f] = Box();
      for (Index u : surface_.triangles[f]) face_reach_[f].add(vertex_reach_[u]);
      faces_.insert(f, face_reach_[f].lo, face_reach_[f].hi);
    }
    incidence_[v].clear();
    if (auto it = occupied_.find(surface_.positions[v]); it != occupied_.end() && it->second == v)
      occupied_.erase(it);
    on_grid_[v] = 1;
    collapsed_[v] = 1;
  }

  // Drops the faces and vertices the collapses removed (attributes follow).
  void remove_collapsed() {
    std::vector<Triangle> faces;
    for (std::size_t f = 0; f < surface_.triangles.size(); ++f)
      if (!removed_[f]) faces.push_back(surface_.triangles[f]);
    std::vector<Index> remap(surface_.positions.size());
    Index next = 0;
    for (std::size_t v = 0; v < remap.size(); ++v) remap[v] = collapsed_[v] ? 0 : next++;
    const auto compact = [&](auto& values) {
      if (values.empty()) return;
      std::size_t out = 0;
      for (std::size_t v = 0; v < values.size(); ++v)
        if (!collapsed_[v]) values[out++] = values[v];
      values.resize(out);
    };
    compact(surface_.positions);
    compact(surface_.normals);
    compact(surface_.uvs);
    compact(surface_.colors);
    for (Triangle& t : faces)
      for (Index& u : t) u = remap[u];
    surface_.triangles = std::move(faces);
    if (!surface_.face_regions.empty()) {
      std::vector<std::int32_t> regions;
      for (std::size_t f = 0; f < removed_.size(); ++f)
        if (!removed_[f]) regions.push_back(surface_.face_regions[f]);
      surface_.face_regions = std::move(regions);
    }
  }

  // Every box a vertex can be in during the stage (its position and the grid
  // points it may try), and per face the union of its vertices': two faces
  // can only come to meet if these overlap.
  void build_reach() {
    vertex_reach_.resize(original_.size());
    Box all;
    double total_size = 0.0;
    for (std::size_t v = 0; v < original_.size(); ++v) {
      Box& b = vertex_reach_[v];
      b.add(original_[v]);
      const Vec3d n = grid_.nearest(original_[v]);
      const int reach = options_.max_steps * options_.max_stride;
      for (int axis = 0; axis < 3; ++axis) {
        b.lo[axis] = std::min(b.lo[axis], grid_.step(axis, n[axis], -reach));
        b.hi[axis] = std::max(b.hi[axis], grid_.step(axis, n[axis], reach));
      }
      all.add(b);
    }
    face_reach_.resize(surface_.triangles.size());
    for (std::size_t f = 0; f < surface_.triangles.size(); ++f) {
      for (Index v : surface_.triangles[f]) face_reach_[f].add(vertex_reach_[v]);
      total_size += (face_reach_[f].hi - face_reach_[f].lo).maxCoeff();
    }
    if (face_reach_.empty()) return;
    const double mean = total_size / double(face_reach_.size());
    const double cell = std::max({2.0 * mean, (all.hi - all.lo).maxCoeff() / 2000.0, 1e-300});
    faces_ = spatial::BoxGrid(all.lo - Vec3d::Constant(cell), cell);
    for (std::size_t f = 0; f < face_reach_.size(); ++f)
      faces_.insert(static_cast<std::uint32_t>(f), face_reach_[f].lo, face_reach_[f].hi);
  }

  std::span<const Index> faces_around(Index v) const { return incidence_[v]; }

  // The nearest grid point; when searching, the points around it, in
  // widening lattices (every step, then every 4th, 16th, ...) so that a
  // vertex that must move past a near sheet or a sliver finds a place.
  void place(Index v, bool search, GridRoundingStats& stats) {
    const std::vector<Index> nearby = faces_near(v);
    forget_refusal_unless_near(v, nearby);
    // Not a value the file would store at another level (a fine Draco grid).
    const auto try_grid_point = [&](const Vec3d& c) { return grid_.holds(c) && try_position(v, c, nearby); };
    const Vec3d nearest = grid_.nearest(original_[v]);
    bool placed = try_grid_point(nearest);
    for (int stride = 1; !placed && search && stride <= options_.max_stride; stride *= 4) {
      for (const Vec3d& c : ring_candidates(v, nearest, stride))
        if ((placed = try_grid_point(c))) break;
      if (placed) ++stats.nearest_refused;
    }
    if (placed) stats.max_move = std::max(stats.max_move, (surface_.positions[v] - original_[v]).norm());
  }

  // Faces that may meet a face around v while v moves, not around v themselves.
  std::vector<Index> faces_near(Index v) const {
    Box reach;
    for (Index f : faces_around(v)) reach.add(face_reach_[f]);
    std::vector<std::uint32_t> found;
    faces_.query(reach.lo, reach.hi, found);
    std::vector<Index> out;
    const std::span<const Index> around = faces_around(v);
    for (std::uint32_t g : found)
      if (std::find(around.begin(), around.end(), g) == around.end()) out.push_back(g);
    return out;
  }

  // Grid points up to max_steps strides of `stride` steps from `nearest`
  // along each axis, nearest to the original position first (ties: by
  // offset, so the order is fixed).
  std::vector<Vec3d> ring_candidates(Index v, const Vec3d& nearest, int stride) const {
    const int r = options_.max_steps;
    std::vector<std::array<double, 3>> axis_values(static_cast<std::size_t>(2 * r + 1));
    for (int i = -r; i <= r; ++i)
      for (int axis = 0; axis < 3; ++axis)
        axis_values[static_cast<std::size_t>(i + r)][static_cast<std::size_t>(axis)] =
            grid_.step(axis, nearest[axis], i * stride);
    std::vector<std::tuple<double, int, int, int>> order;
    for (int i = -r; i <= r; ++i)
      for (int j = -r; j <= r; ++j)
        for (int k = -r; k <= r; ++k) {
          if (i == 0 && j == 0 && k == 0) continue;
          const Vec3d c = candidate(axis_values, r, i, j, k);
          order.emplace_back((c - original_[v]).squaredNorm(), i, j, k);
        }
    std::sort(order.begin(), order.end());
    std::vector<Vec3d> out;
    for (const auto& [distance, i, j, k] : order) {
      const Vec3d c = candidate(axis_values, r, i, j, k);
      if (out.empty() || out.back() != c) out.push_back(c);
    }
    return out;
  }

  static Vec3d candidate(const std::vector<std::array<double, 3>>& values, int r, int i, int j, int k) {
    return {values[static_cast<std::size_t>(i + r)][0], values[static_cast<std::size_t>(j + r)][1],
            values[static_cast<std::size_t>(k + r)][2]};
  }

  std::array<Vec3d, 3> corners(Index f, Index v, const Vec3d& at) const {
    std::array<Vec3d, 3> c;
    for (int k = 0; k < 3; ++k) {
      const Index w = surface_.triangles[f][static_cast<std::size_t>(k)];
      c[static_cast<std::size_t>(k)] = w == v ? at : surface_.positions[w];
    }
    return c;
  }

  // The face that refused v last is asked first only while it is near v
  // (a collapse since may have moved v's faces elsewhere).
  void forget_refusal_unless_near(Index v, const std::vector<Index>& nearby) {
    Index& last = last_refusal_[v];
    if (last != kNoFace && std::find(nearby.begin(), nearby.end(), last) == nearby.end()) last = kNoFace;
  }

  // Moves v to c if that keeps the surface valid, exactly; true if it did.
  // Precondition: v's last refusal is kNoFace or among `nearby`.
  bool try_position(Index v, const Vec3d& c, const std::vector<Index>& nearby) {
    count_try();
    if (auto it = occupied_.find(c); it != occupied_.end() && it->second != v) return false;
    MovedFaces moved;
    for (Index f : faces_around(v)) {
      const std::array<Vec3d, 3>& m = moved.corners.emplace_back(corners(f, v, c));
      if (collinear(m[0], m[1], m[2])) return false;
      moved.boxes.push_back(box_of(m));
      moved.planes.emplace_back(m[0], m[1], m[2]);
    }
    // The face that refused v's last candidate usually refuses the next one
    // too (a sheet closer than a grid step): asked first, it saves scanning
    // every face near v with exact tests that coplanar sheets make slow.
    Index& last = last_refusal_[v];
    if (last != kNoFace && meets_moved(moved, last, v, c)) return false;
    for (std::size_t i = 0; i < moved.corners.size(); ++i)
      for (std::size_t j = i + 1; j < moved.corners.size(); ++j)
        if (improper(moved.corners[i], moved.corners[j])) return false;
    for (Index g : nearby) {
      if (g != last && meets_moved(moved, g, v, c)) {
        last = g;
        return false;
      }
    }
    move(v, c);
    return true;
  }

  void count_try() {
    if (++tries_ <= options_.max_tries || options_.max_tries == 0) return;
    throw RunError("gave up placing the vertices on the " + grid_.name() + " grid of the output after " +
                   std::to_string(options_.max_tries) + " tried positions");
  }

  static bool improper(const std::array<Vec3d, 3>& a, const std::array<Vec3d, 3>& b) {
    return intersect_triangles(a[0], a[1], a[2], b[0], b[1], b[2]).improper();
  }

  static Box box_of(const std::array<Vec3d, 3>& corners) {
    Box box;
    for (const Vec3d& p : corners) box.add(p);
    return box;
  }

  // The faces around a vertex, moved with it, their boxes and planes.
  struct MovedFaces {
    std::vector<std::array<Vec3d, 3>> corners;
    std::vector<Box> boxes;
    std::vector<PlaneSideFilter> planes;
  };

  // Whether face g (not around v) meets one of v's faces moved with v to c improperly.
  bool meets_moved(const MovedFaces& moved, Index g, Index v, const Vec3d& c) const {
    if (removed_[g]) return false;
    const std::array<Vec3d, 3> other = corners(g, v, c);
    const Box box_g = box_of(other);
    // Beside long slivers most faces near v lie wholly on one side of a
    // moved face's plane: the filter spares their exact tests.
    for (std::size_t i = 0; i < moved.corners.size(); ++i)
      if (moved.boxes[i].overlaps(box_g) &&
          !certainly_apart_but_shared(moved.planes[i], moved.corners[i], other) &&
          improper(moved.corners[i], other))
        return true;
    return false;
  }

  void move(Index v, const Vec3d& c) {
    if (auto it = occupied_.find(surface_.positions[v]); it != occupied_.end() && it->second == v)
      occupied_.erase(it);
    surface_.positions[v] = c;
    occupied_[c] = v;
    on_grid_[v] = 1;
  }

  TriangleSoup& surface_;
  const CoordinateGrid& grid_;
  GridRoundingOptions options_;
  std::vector<Vec3d> original_;
  Incidence incidence_;
  std::vector<std::uint8_t> on_grid_;
  std::vector<std::uint8_t> collapsed_;  ///< per vertex: collapsed away
  std::vector<std::uint8_t> removed_;    ///< per face: removed by a collapse
  std::vector<Index> last_refusal_;      ///< per vertex: the face that refused its last candidate
  std::size_t tries_ = 0;                ///< positions tried so far
  std::unordered_map<Vec3d, Index, PositionHash, PositionEqual> occupied_;
  std::vector<Box> vertex_reach_;
  std::vector<Box> face_reach_;
  spatial::BoxGrid faces_;
};

// The search on a grid that is not the only one: a few positions per
// vertex and about one full search (GridRoundingOptions' defaults) besides.
constexpr std::size_t kTriesPerVertex = 4;
constexpr std::size_t kTriesPerGrid = 20000;

}  // namespace

GridRoundingStats round_to_grid(TriangleSoup& surface, const CoordinateGrid& grid,
                                const GridRoundingOptions& options) {
  if (options.max_steps < 0 || options.max_stride < 1 || options.max_passes < 1)
    throw UsageError("round_to_grid: max_steps must be >= 0, max_stride and max_passes >= 1");
  if (grid.is_identity()) {
    GridRoundingStats stats;
    stats.vertices = surface.positions.size();
    return stats;
  }
  for (const Vec3d& p : surface.positions)
    if (!grid.nearest(p).allFinite())
      throw RunError("a coordinate of the surface lies outside the range of the output's " + grid.name() +
                     " grid");
  return VertexPlacement(surface, grid, options).run();
}

GridRounding round_to_grid_or_finer(TriangleSoup& surface, const CoordinateGrid& grid, const FinerGrid& finer,
                                    const GridRoundingOptions& options) {
  GridRounding result{grid, {}, 0};
  const TriangleSoup unrounded = surface;
  while (true) {
    std::optional<CoordinateGrid> next;
    if (finer) next = finer(result.grid);
    GridRoundingOptions attempt = options;
    if ((next || result.finer_grids > 0) && attempt.max_tries == 0)
      attempt.max_tries = kTriesPerVertex * surface.positions.size() + kTriesPerGrid;
    try {
      result.stats = round_to_grid(surface, result.grid, attempt);
      return result;
    } catch (const RunError&) {
      if (!next) throw;
      surface = unrounded;
      result.grid = *next;
      ++result.finer_grids;
    }
  }
}

}  // namespace mr::repair
