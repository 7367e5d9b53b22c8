#include "regions.h"

#include <mr/core/orientation.h>

#include <mr/kernel/predicates.h>
#include <mr/spatial/aabb_tree.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>

namespace mr::tetmesh::detail {

std::vector<std::int32_t> region_labels(const Mesh& mesh, std::span<const char> barrier) {
  const auto blocked = [&](Index t) { return !barrier.empty() && barrier[t] != 0; };
  std::vector<std::int32_t> labels(mesh.tet_slots(), 0);
  std::int32_t next = 0;
  std::vector<Index> stack;
  for (Index seed = 0; seed < mesh.tet_slots(); ++seed) {
    if (!mesh.tet_alive(seed) || labels[seed] != 0) continue;
    labels[seed] = ++next;
    if (blocked(seed)) continue;
    stack.push_back(seed);
    while (!stack.empty()) {
      const Index t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 4; ++k) {
        const Index n = mesh.neighbour(t, k);
        if (n == kNoTet || labels[n] != 0 || mesh.is_surface_face(t, k) || blocked(n)) continue;
        labels[n] = next;
        stack.push_back(n);
      }
    }
  }
  return labels;
}

Vec3d input_normal(const TriangleSoup& input, std::uint32_t id) {
  const Triangle& t = input.triangles[id];
  return (input.positions[t[1]] - input.positions[t[0]])
      .cross(input.positions[t[2]] - input.positions[t[0]])
      .normalized();
}

namespace {

// +1 when face k of tet t, oriented out of t, runs like input triangle id,
// -1 when against it. Decided by the exact side, with respect to the
// triangle's plane, of the opposite corner of t or of its neighbour across
// the face, whichever lies farther from the plane (the face's own normal is
// noise for the tiny faces rounding leaves between nearly coincident cut
// points); from the normals when both corners are on the plane. Rounding
// and collapses moved the face off the plane by a little, so a corner that
// is nearly on the plane (a sliver's) may be on the wrong side of it: on
// thingi10k/1514499 trusting the tet's own corner first broke the chain of
// a closed input (edges not run along as often each way).
int face_direction(const Mesh& mesh, Index t, int k, const TriangleSoup& input, std::uint32_t id,
                   const Vec3d& face_normal) {
  const Triangle& tri = input.triangles[id];
  const Vec3d normal = input_normal(input, id);
  const Vec3d& origin = input.positions[tri[0]];
  const auto side = [&](Index v) {
    return orient3d(HybridPoint(input.positions[tri[0]]), HybridPoint(input.positions[tri[1]]),
                    HybridPoint(input.positions[tri[2]]), mesh.position(v));
  };
  const auto distance = [&](Index v) { return std::abs((mesh.position(v).approx - origin).dot(normal)); };
  // A corner below the plane on t's side: the outward normal points up;
  // below it on the neighbour's side: the outward normal points down.
  int direction = 0;
  double farthest = -1.0;
  const Index own = mesh.tet(t)[k];
  if (const int s = side(own); s != 0) {
    direction = -s;
    farthest = distance(own);
  }
  const Index n = mesh.neighbour(t, k);
  if (n != kNoTet) {
    const Index other = mesh.tet(n)[mesh.face_towards(n, t)];
    if (const int s = side(other); s != 0 && distance(other) > farthest) direction = s;
  }
  if (direction != 0) return direction;
  return face_normal.dot(normal) < 0 ? -1 : 1;
}

}  // namespace

TriangleSoup tracked_surface(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input,
                             Multiplicity multiplicity, std::vector<FaceRef>* origins) {
  const auto kept = [&](Index t) {
    return t != kNoTet && mesh.tet_alive(t) && (keep.empty() || keep[t] != 0);
  };
  TriangleSoup surface;
  std::vector<double> votes;
  std::vector<Index> used(mesh.vertex_slots(), kNoVertex);
  const auto emit = [&](const std::array<Index, 3>& f, double vote, FaceRef origin) {
    if (origins != nullptr) origins->push_back(origin);
    Triangle out;
    for (int i = 0; i < 3; ++i) {
      if (used[f[i]] == kNoVertex) {
        used[f[i]] = static_cast<Index>(surface.positions.size());
        surface.positions.push_back(mesh.position(f[i]).approx);
      }
      out[i] = used[f[i]];
    }
    surface.triangles.push_back(out);
    votes.push_back(vote);
  };
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!kept(t)) continue;
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.neighbour(t, k);
      if (!mesh.is_surface_face(t, k) || (kept(n) && n < t)) continue;
      std::array<Index, 3> f = mesh.face_vertices(t, k);
      const Vec3d& a = mesh.position(f[0]).approx;
      const Vec3d normal = (mesh.position(f[1]).approx - a).cross(mesh.position(f[2]).approx - a);
      const auto ids = mesh.surface_ids(t, k);
      if (multiplicity == Multiplicity::once) {
        const int direction = face_direction(mesh, t, k, input, ids.front(), normal);
        if (direction < 0) std::swap(f[1], f[2]);
        emit(f, std::max(0.0, direction * normal.dot(input_normal(input, ids.front()))), {t, k});
        continue;
      }
      // As a chain: each input triangle on the face counts +1 or -1 by how
      // the face runs relative to it, so coincident faces of two parts that
      // touch (opposite orientations) cancel, and duplicates add up.
      int net = 0;
      double agreement = 0.0;
      for (const std::uint32_t id : ids) {
        const int direction = face_direction(mesh, t, k, input, id, normal);
        net += direction;
        agreement += std::max(0.0, direction * normal.dot(input_normal(input, id)));
      }
      if (net == 0) continue;
      if (net < 0) std::swap(f[1], f[2]);
      for (int copy = 0; copy < std::abs(net); ++copy)
        emit(f, agreement / static_cast<double>(ids.size()), {t, k});
    }
  }
  // The normal test above is only a guess for faces that moved away from
  // the plane of their input triangle (improvement, or faces merged across a
  // crease): orient each patch coherently, trusting faces by how well
  // their normal agreed with their triangle's.
  orient_coherently(surface, votes);
  return surface;
}

std::vector<std::array<Index, 2>> chain_boundary(const TriangleSoup& surface) {
  // +1 for each use of edge (lo, hi) from lo to hi, -1 the other way. An
  // edge from a vertex to itself (a triangle with two corners welded, as
  // snapping makes) is no edge: it bounds nothing.
  std::vector<std::pair<std::array<Index, 2>, int>> uses;
  uses.reserve(3 * surface.triangles.size());
  for (const Triangle& t : surface.triangles) {
    for (int i = 0; i < 3; ++i) {
      const Index a = t[i], b = t[(i + 1) % 3];
      if (a == b) continue;
      uses.push_back({{std::min(a, b), std::max(a, b)}, a < b ? 1 : -1});
    }
  }
  std::sort(uses.begin(), uses.end());
  std::vector<std::array<Index, 2>> boundary;
  for (std::size_t i = 0; i < uses.size();) {
    int net = 0;
    std::size_t j = i;
    for (; j < uses.size() && uses[j].first == uses[i].first; ++j) net += uses[j].second;
    const auto [lo, hi] = uses[i].first;
    for (int copy = 0; copy < std::abs(net); ++copy)
      boundary.push_back(net > 0 ? std::array<Index, 2>{lo, hi} : std::array<Index, 2>{hi, lo});
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  return boundary;
}

std::vector<std::array<Index, 2>> unbalanced_edges(const TriangleSoup& surface) {
  std::vector<std::array<Index, 2>> edges = chain_boundary(surface);
  for (auto& e : edges)
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

bool is_cycle(const TriangleSoup& surface) { return unbalanced_edges(surface).empty(); }

std::size_t edges_away_from(const TriangleSoup& surface, std::span<const std::array<Index, 2>> edges,
                            const TriangleSoup& triangles, double radius) {
  if (triangles.triangles.empty()) return edges.size();
  const spatial::AabbTree tree(triangles);
  return static_cast<std::size_t>(
      std::count_if(edges.begin(), edges.end(), [&](const std::array<Index, 2>& e) {
        return !tree.any_within(0.5 * (surface.positions[e[0]] + surface.positions[e[1]]), radius);
      }));
}

std::size_t count_non_positive_tets(const TetMesh& mesh) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.tets.size()), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t count) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const Tet& t = mesh.tets[i];
          count += orient3d(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                            mesh.positions[t[3]]) <= 0;
        }
        return count;
      },
      std::plus<>());
}

}  // namespace mr::tetmesh::detail
