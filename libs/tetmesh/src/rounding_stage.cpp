#include "rounding_stage.h"

#include "vertex_collapse.h"

#include <mr/kernel/rounding.h>
#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <vector>

namespace mr::tetmesh::detail {
namespace {

bool round_vertex(Mesh& mesh, Index v, std::span<const Index> star) {
  std::vector<OppositeFace> faces;
  faces.reserve(star.size());
  for (Index t : star) {
    const auto f = opposite_face(mesh.tet(t), mesh.corner_of(t, v));
    faces.push_back({&mesh.position(f[0]), &mesh.position(f[1]), &mesh.position(f[2])});
  }
  return try_round(mesh.position(v), faces);
}

// The corners of the star other than v within `max_distance`, nearest first.
std::vector<Index> nearby_neighbours(const Mesh& mesh, Index v, std::span<const Index> star,
                                     double max_distance) {
  std::vector<Index> neighbours;
  for (Index t : star) {
    for (Index u : mesh.tet(t)) {
      if (u != v) neighbours.push_back(u);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  const Vec3d& p = mesh.position(v).approx;
  const auto distance = [&](Index u) { return (mesh.position(u).approx - p).norm(); };
  std::erase_if(neighbours, [&](Index u) { return distance(u) > max_distance; });
  std::stable_sort(neighbours.begin(), neighbours.end(),
                   [&](Index a, Index b) { return distance(a) < distance(b); });
  return neighbours;
}

// The vertices within `max_distance` of v reachable from it through such
// vertices (v included), at most kMaxCluster of them: a knot of points
// closer than a rounding step that must be merged together.
constexpr std::size_t kMaxCluster = 16;

std::vector<Index> cluster_around(const Mesh& mesh, const VertexTets& incidence, Index v,
                                  double max_distance) {
  std::vector<Index> cluster{v};
  const Vec3d& p = mesh.position(v).approx;
  for (std::size_t i = 0; i < cluster.size() && cluster.size() < kMaxCluster; ++i) {
    for (Index u : nearby_neighbours(mesh, cluster[i], incidence.of(cluster[i]), max_distance)) {
      if ((mesh.position(u).approx - p).norm() > max_distance) continue;
      if (std::find(cluster.begin(), cluster.end(), u) == cluster.end()) cluster.push_back(u);
    }
  }
  return cluster;
}

std::vector<Index> union_of_stars(const VertexTets& incidence, std::span<const Index> vertices) {
  std::vector<Index> star;
  for (Index v : vertices) star.insert(star.end(), incidence.of(v).begin(), incidence.of(v).end());
  std::sort(star.begin(), star.end());
  star.erase(std::unique(star.begin(), star.end()), star.end());
  return star;
}

class Sweep {
 public:
  Sweep(Mesh& mesh, double max_distance)
      : mesh_(mesh), incidence_(mesh), touched_(mesh.vertex_slots(), 0), max_distance_(max_distance) {}

  RoundingCounters run() {
    for (Index v = 0; v < mesh_.vertex_slots(); ++v) {
      if (!mesh_.vertex_alive(v) || !mesh_.position(v).is_exact()) continue;
      if (touched_[v] != 0) {
        ++counters_.remaining;
        continue;
      }
      const std::span<const Index> star = incidence_.of(v);
      if (round_vertex(mesh_, v, star)) {
        ++counters_.rounded;
      } else if (collapse_onto_neighbour(v) || collapse_cluster(v)) {
        ++counters_.collapsed;
      } else {
        ++counters_.remaining;
      }
    }
    return counters_;
  }

 private:
  // The vertices `removed` collapsed onto the first of `targets` that takes them.
  bool try_collapse(std::span<const Index> removed, std::span<const Index> targets) {
    for (Index w : removed) {
      if (touched_[w] != 0) return false;
    }
    const std::vector<Index> star = union_of_stars(incidence_, removed);
    const StarBoundary boundary = star_boundary(mesh_, removed, star);
    std::vector<Index> corners;  // the vertices whose stars the collapse changes
    for (Index t : star) corners.insert(corners.end(), mesh_.tet(t).begin(), mesh_.tet(t).end());
    for (Index u : targets) {
      if (!collapse_vertices(mesh_, removed, u, star, boundary)) continue;
      for (Index w : corners) touched_[w] = 1;
      return true;
    }
    return false;
  }

  bool collapse_onto_neighbour(Index v) {
    return try_collapse(std::span<const Index>(&v, 1),
                        nearby_neighbours(mesh_, v, incidence_.of(v), max_distance_));
  }

  // Merges the whole knot around v into one of its points, a double one
  // first (nearest first).
  bool collapse_cluster(Index v) {
    const std::vector<Index> cluster = cluster_around(mesh_, incidence_, v, max_distance_);
    if (cluster.size() < 3) return false;  // a pair was tried by collapse_onto_neighbour
    std::vector<Index> targets(cluster.begin() + 1, cluster.end());
    std::stable_partition(targets.begin(), targets.end(),
                          [&](Index u) { return !mesh_.position(u).is_exact(); });
    for (Index u : targets) {
      std::vector<Index> removed;
      for (Index w : cluster) {
        if (w != u) removed.push_back(w);
      }
      if (try_collapse(removed, std::span<const Index>(&u, 1))) return true;
    }
    return false;
  }

  Mesh& mesh_;
  const VertexTets incidence_;
  std::vector<char> touched_;
  double max_distance_;
  RoundingCounters counters_;
};

}  // namespace

RoundingCounters round_or_collapse(Mesh& mesh, double max_collapse_distance) {
  RoundingCounters total;
  while (true) {
    const RoundingCounters pass = Sweep(mesh, max_collapse_distance).run();
    total.rounded += pass.rounded;
    total.collapsed += pass.collapsed;
    total.remaining = pass.remaining;
    if (pass.remaining == 0 || pass.rounded + pass.collapsed == 0) return total;
  }
}

}  // namespace mr::tetmesh::detail
