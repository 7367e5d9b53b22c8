// The adaptive sizing of the improvement (paper section 3.2, "the target
// edge length is reduced where the energy stays high"): when the passes
// stall, the local target shrinks around bad tets, smoothly with distance,
// and grows back elsewhere, between a floor and the global target.

#include "improve_local.h"

#include <mr/tetmesh/incidence.h>

#include <algorithm>
#include <deque>

namespace mr::tetmesh::improve_detail {
namespace {

constexpr double kShrink = 0.5;     // factor at a vertex of a bad tet
constexpr double kRecover = 1.5;    // factor everywhere else
constexpr double kReach = 1.8;      // radius of the shrinking, in local target lengths
constexpr double kMaxFilter = 100;  // tets above this energy always count as bad

// Tets above this energy seed the shrinking: the worst ones first while the
// largest energy is huge, then every tet near the stop energy.
double filter_energy(double max_energy, double stop_energy) {
  return std::min(kMaxFilter, std::max(max_energy / 100, 0.8 * stop_energy));
}

struct Visit {
  Index vertex;
  Index seed;
};

}  // namespace

SizingUpdate update_sizing(Workspace& ws, std::span<const double> energy, double max_energy,
                           double min_scale) {
  Mesh& mesh = ws.mesh;
  if (ws.sizing.size() < mesh.vertex_slots()) ws.sizing.resize(mesh.vertex_slots(), 1.0);
  const double filter = filter_energy(max_energy, ws.stop_energy);
  const VertexTets incidence(mesh);
  std::vector<double> factor(mesh.vertex_slots(), kRecover);
  std::vector<char> visited(mesh.vertex_slots(), 0);
  std::deque<Visit> queue;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || energy[t] <= filter) continue;
    for (const Index v : mesh.tet(t)) {
      if (visited[v]) continue;
      visited[v] = 1;
      factor[v] = kShrink;
      queue.push_back({v, v});
    }
  }
  // Breadth first from the seeds: a vertex takes the factor of the first
  // seed that reaches it, growing linearly to 1 at the seed's radius.
  while (!queue.empty()) {
    const Visit at = queue.front();
    queue.pop_front();
    const double radius = kReach * ws.target_edge_length * ws.scale(at.seed);
    const Vec3d& origin = mesh.position(at.seed).approx;
    for (const Index t : incidence.of(at.vertex)) {
      for (const Index w : mesh.tet(t)) {
        if (visited[w]) continue;
        const double distance = (mesh.position(w).approx - origin).norm();
        if (distance >= radius) continue;
        visited[w] = 1;
        factor[w] = std::min(factor[w], kShrink + (1 - kShrink) * distance / radius);
        queue.push_back({w, at.seed});
      }
    }
  }
  SizingUpdate out;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    const double scaled = ws.sizing[v] * factor[v];
    if (scaled < min_scale) out.hit_floor = true;
    out.shrunk += factor[v] < 1;
    ws.sizing[v] = std::clamp(scaled, min_scale, 1.0);
  }
  return out;
}

}  // namespace mr::tetmesh::improve_detail
