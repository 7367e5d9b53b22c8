#include "vertex_split.h"

#include <mr/kernel/intersections.h>
#include <mr/kernel/predicates.h>

#include <algorithm>
#include <array>

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

}  // namespace

spatial::BoxGrid grid_of_boundary(const TetMesh& mesh, const std::vector<FaceRef>& boundary,
                                  double max_move) {
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
  spatial::BoxGrid grid(all.lo, cell);
  for (std::size_t i = 0; i < boxes.size(); ++i)
    grid.insert(static_cast<std::uint32_t>(i), boxes[i].lo, boxes[i].hi);
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
