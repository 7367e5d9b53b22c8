#include <mr/tetmesh/winding_filter.h>

#include <mr/core/errors.h>

#include <cmath>
#include <string>

namespace mr::tetmesh {

Vec3d tet_centroid(const Mesh& mesh, Index t) {
  const Tet& c = mesh.tet(t);
  return 0.25 * (mesh.position(c[0]).approx + mesh.position(c[1]).approx + mesh.position(c[2]).approx +
                 mesh.position(c[3]).approx);
}

bool is_inside(double winding, WindingRule rule) {
  return (rule == WindingRule::absolute ? std::abs(winding) : winding) > 0.5;
}

TetClassification classify_tets(const Mesh& mesh, const WindingNumberTree& tree, WindingRule rule) {
  std::vector<Vec3d> centroids;
  std::vector<Index> slots;
  centroids.reserve(mesh.num_tets());
  slots.reserve(mesh.num_tets());
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    centroids.push_back(tet_centroid(mesh, t));
    slots.push_back(t);
  }
  const std::vector<double> values = tree.evaluate(centroids);
  TetClassification result;
  result.winding.assign(mesh.tet_slots(), 0.0);
  result.keep.assign(mesh.tet_slots(), 0);
  for (std::size_t i = 0; i < slots.size(); ++i) {
    result.winding[slots[i]] = values[i];
    if (is_inside(values[i], rule)) {
      result.keep[slots[i]] = 1;
      ++result.kept;
    }
  }
  return result;
}

TetMesh extract_tets(const Mesh& mesh, std::span<const char> keep) {
  if (keep.size() != mesh.tet_slots()) {
    throw UsageError("extract_tets: " + std::to_string(keep.size()) + " flags for " +
                     std::to_string(mesh.tet_slots()) + " tet slots");
  }
  std::vector<Index> new_index(mesh.vertex_slots(), kNoVertex);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!keep[t]) continue;
    if (!mesh.tet_alive(t)) throw UsageError("extract_tets: removed tet " + std::to_string(t) + " kept");
    for (const Index v : mesh.tet(t)) new_index[v] = 0;
  }
  TetMesh out;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (new_index[v] == kNoVertex) continue;
    if (mesh.position(v).is_exact()) {
      throw RunError("extract_tets: vertex " + std::to_string(v) + " of a kept tet is still rational");
    }
    new_index[v] = static_cast<Index>(out.positions.size());
    out.positions.push_back(mesh.position(v).approx);
  }
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!keep[t]) continue;
    Tet tet = mesh.tet(t);
    for (Index& v : tet) v = new_index[v];
    out.tets.push_back(tet);
  }
  return out;
}

}  // namespace mr::tetmesh
