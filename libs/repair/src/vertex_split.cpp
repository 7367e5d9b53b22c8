#include "vertex_split.h"

#include <mr/kernel/intersections.h>
#include <mr/kernel/predicates.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace mr::repair::detail {
namespace {

using Corners = std::array<Vec3d, 4>;

struct Box {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d hi = -Vec3d::Constant(std::numeric_limits<double>::infinity());
  void add(const Vec3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool overlaps(const Box& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

Box box_of(const std::vector<Vec3d>& positions, const Triangle& t) {
  Box box;
  for (Index v : t) box.add(positions[v]);
  return box;
}

void rename(TetMesh& mesh, std::span<const Index> tets, Index from, Index to) {
  for (Index t : tets) std::replace(mesh.tets[t].begin(), mesh.tets[t].end(), from, to);
}

// p lies strictly inside the tet with these corners.
bool strictly_inside(const Corners& corners, const Vec3d& p) {
  for (int i = 0; i < 4; ++i) {
    Corners c = corners;
    c[i] = p;
    if (orient3d(c[0], c[1], c[2], c[3]) <= 0) return false;
  }
  return true;
}

bool all_positive(const TetMesh& mesh, std::span<const Index> tets) {
  const auto& p = mesh.positions;
  return std::all_of(tets.begin(), tets.end(), [&](Index t) {
    const Tet& c = mesh.tets[t];
    return orient3d(p[c[0]], p[c[1]], p[c[2]], p[c[3]]) > 0;
  });
}

int shared_indices(const Triangle& a, const Triangle& b) {
  int n = 0;
  for (Index v : a) n += std::find(b.begin(), b.end(), v) != b.end();
  return n;
}

// Two boundary faces may meet only in what their indices share.
bool meet_properly(const std::vector<Vec3d>& p, const Triangle& f, const Triangle& g) {
  const TriangleTriangleHit hit = intersect_triangles(p[f[0]], p[f[1]], p[f[2]], p[g[0]], p[g[1]], p[g[2]]);
  const int shared = shared_indices(f, g);
  switch (hit.kind) {
    case TriangleTriangleKind::disjoint:
      return true;
    case TriangleTriangleKind::shared_vertex:
      return shared == 1 && hit.shared_vertices == 1;
    case TriangleTriangleKind::shared_edge:
      return shared == 2;
    default:
      return false;
  }
}

// The boundary faces around w meet no boundary face improperly.
bool new_faces_apart(const SplitContext& context, Index w, std::span<const Index> tets) {
  const TetMesh& mesh = context.mesh;
  std::vector<std::pair<Triangle, FaceRef>> around;
  Box reach;
  for (Index t : tets)
    for (int k = 0; k < 4; ++k) {
      const Triangle f = tet_face(mesh.tets[t], k);
      if (!on_boundary(context.neighbours, context.states, t, k) ||
          std::find(f.begin(), f.end(), w) == f.end())
        continue;
      around.push_back({f, {t, k}});
      for (Index v : f) reach.add(mesh.positions[v]);
    }
  std::vector<std::uint32_t> nearby;
  context.boundary_grid.query(reach.lo, reach.hi, nearby);
  for (std::uint32_t i : nearby) {
    const FaceRef& other = context.boundary[i];
    const Triangle g = tet_face(mesh.tets[other.tet], other.face);
    const Box g_box = box_of(mesh.positions, g);
    if (!g_box.overlaps(reach)) continue;
    for (const auto& [f, ref] : around) {
      if (ref.tet == other.tet && ref.face == other.face) continue;
      if (g_box.overlaps(box_of(mesh.positions, f)) && !meet_properly(mesh.positions, f, g)) return false;
    }
  }
  return true;
}

Index largest_tet(const TetMesh& mesh, std::span<const Index> tets) {
  return *std::max_element(tets.begin(), tets.end(), [&](Index a, Index b) {
    return tet_volume(mesh.positions, mesh.tets[a]) < tet_volume(mesh.positions, mesh.tets[b]);
  });
}

// Moves w (now at the shared position) towards the centroid of the largest
// tet of its class, halving the step until every check passes.
bool move_into_class(const SplitContext& context, Index w, std::span<const Index> tets) {
  std::vector<Vec3d>& positions = context.mesh.positions;
  const Vec3d origin = positions[w];
  const Tet& room = context.mesh.tets[largest_tet(context.mesh, tets)];
  const Corners corners{positions[room[0]], positions[room[1]], positions[room[2]], positions[room[3]]};
  const Vec3d direction = (corners[0] + corners[1] + corners[2] + corners[3]) / 4.0 - origin;
  const double length = direction.norm();
  if (!(length > 0.0)) return false;
  double step = std::min(context.max_move, 0.5 * length);
  constexpr int kAttempts = 40;
  for (int attempt = 0; attempt < kAttempts; ++attempt, step *= 0.5) {
    const Vec3d p = origin + direction * (step / length);
    if (p == origin) break;
    positions[w] = p;
    if (strictly_inside(corners, p) && all_positive(context.mesh, tets) && new_faces_apart(context, w, tets))
      return true;
  }
  positions[w] = origin;
  return false;
}

// Where the boundary faces of a split of v can reach during a round: its
// star's corners as they are now, grown by max_move (v's copy and every
// corner that is itself a copy made this round move at most that far).
Box split_reach(const TetMesh& mesh, std::span<const Index> star, double max_move) {
  Box reach;
  for (Index t : star)
    for (Index u : mesh.tets[t]) reach.add(mesh.positions[u]);
  reach.lo.array() -= max_move;
  reach.hi.array() += max_move;
  return reach;
}

// A coarse map of where splits may reach: kCells^3 cells over `bounds`, a
// cell marked when a reach box meets it. Conservative: a box that meets a
// reach box meets a marked cell.
class ReachMap {
 public:
  ReachMap(const Box& bounds, const std::vector<Box>& reaches) : lo_(bounds.lo) {
    const Vec3d extent = bounds.hi - bounds.lo;
    for (int k = 0; k < 3; ++k) scale_[k] = extent[k] > 0.0 ? kCells / extent[k] : 0.0;
    for (const Box& reach : reaches) visit(reach, [&](std::size_t cell) { marked_[cell] = 1; });
  }
  bool meets(const Box& box) const {
    bool any = false;
    visit(box, [&](std::size_t cell) { any = any || marked_[cell] != 0; });
    return any;
  }

 private:
  static constexpr int kCells = 64;

  // Clamped as a double: a star's corners may lie far outside the bounds.
  int cell(double x, int k) const {
    return static_cast<int>(std::clamp(std::floor((x - lo_[k]) * scale_[k]), 0.0, double(kCells - 1)));
  }
  template <class Visit>
  void visit(const Box& box, Visit&& f) const {
    std::array<int, 3> a{}, b{};
    for (int k = 0; k < 3; ++k) a[k] = cell(box.lo[k], k), b[k] = cell(box.hi[k], k);
    for (int x = a[0]; x <= b[0]; ++x)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int z = a[2]; z <= b[2]; ++z)
          f((std::size_t(x) * kCells + std::size_t(y)) * kCells + std::size_t(z));
  }

  Vec3d lo_;
  std::array<double, 3> scale_{};
  std::vector<char> marked_ = std::vector<char>(std::size_t{kCells} * kCells * kCells, 0);
};

// Per face of `boundary`, whether its box (grown by max_move) may meet the
// reach of a split of one of `to_split`: only those can meet a face the
// split makes. All of them when the vertices are many (late rounds of the
// fix have a few dozen defects on a boundary of 500k faces).
std::vector<char> faces_within_reach(const TetMesh& mesh, const std::vector<Box>& boxes, const Box& bounds,
                                     double max_move, const VertexStars& stars,
                                     std::span<const Index> to_split) {
  constexpr std::size_t kFacesPerVertex = 64;  // below: the filter costs more than it spares
  if (to_split.size() * kFacesPerVertex > boxes.size()) return std::vector<char>(boxes.size(), 1);
  std::vector<Box> reaches;
  for (Index v : to_split) reaches.push_back(split_reach(mesh, stars.of(v), max_move));
  const ReachMap map(bounds, reaches);
  std::vector<char> near(boxes.size(), 0);
  for (std::size_t f = 0; f < boxes.size(); ++f) near[f] = map.meets(boxes[f]) ? 1 : 0;
  return near;
}

}  // namespace

spatial::BoxGrid grid_of_boundary(const TetMesh& mesh, const std::vector<FaceRef>& boundary, double max_move,
                                  const VertexStars& stars, std::span<const Index> to_split) {
  std::vector<Box> boxes;
  boxes.reserve(boundary.size());
  Box all;
  double total_size = 0.0;
  for (const FaceRef& f : boundary) {
    Box box = box_of(mesh.positions, tet_face(mesh.tets[f.tet], f.face));
    box.lo.array() -= max_move;
    box.hi.array() += max_move;
    all.add(box.lo);
    all.add(box.hi);
    total_size += (box.hi - box.lo).maxCoeff();
    boxes.push_back(box);
  }
  if (boxes.empty()) return {};
  const double cell = std::max(2.0 * total_size / double(boxes.size()), 1e-300);
  const std::vector<char> near = faces_within_reach(mesh, boxes, all, max_move, stars, to_split);
  spatial::BoxGrid grid(all.lo, cell);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (near[i] != 0) grid.insert(static_cast<std::uint32_t>(i), boxes[i].lo, boxes[i].hi);
  return grid;
}

std::size_t split_vertex(const SplitContext& context, Index v, std::span<const Index> star) {
  std::vector<Index> solid;
  for (Index t : star)
    if (in_solid(context.states[t])) solid.push_back(t);
  const std::vector<std::vector<Index>> classes = face_connected_classes(context.neighbours, solid);
  std::size_t copies = 0;
  TetMesh& mesh = context.mesh;
  for (std::size_t c = 1; c < classes.size(); ++c) {
    const Index copy = static_cast<Index>(mesh.positions.size());
    mesh.positions.push_back(mesh.positions[v]);
    rename(mesh, classes[c], v, copy);
    if (move_into_class(context, copy, classes[c])) {
      ++copies;
      continue;
    }
    rename(mesh, classes[c], copy, v);
    mesh.positions.pop_back();
  }
  if (copies > 0)
    for (Index t : star)
      if (context.states[t] == TetState::rejected) context.states[t] = TetState::locked_out;
  return copies;
}

}  // namespace mr::repair::detail
