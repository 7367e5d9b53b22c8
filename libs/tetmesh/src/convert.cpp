#include <mr/tetmesh/convert.h>

#include <mr/core/errors.h>

#include <string>

namespace mr::tetmesh {

Mesh from_tet_mesh(const TetMesh& input) {
  Mesh mesh;
  for (const Vec3d& p : input.positions) mesh.add_vertex(HybridPoint(p));
  for (const Tet& t : input.tets) {
    for (const Index v : t) {
      if (v >= input.positions.size()) {
        throw UsageError("from_tet_mesh: vertex index " + std::to_string(v) + " out of range");
      }
    }
    mesh.add_tet(t);
  }
  mesh.rebuild_adjacency();
  return mesh;
}

TetMesh to_tet_mesh(const Mesh& mesh) {
  TetMesh out;
  std::vector<Index> new_index(mesh.vertex_slots(), kNoVertex);
  out.positions.reserve(mesh.num_vertices());
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    if (mesh.position(v).is_exact()) {
      throw RunError("tet mesh: vertex " + std::to_string(v) +
                     " still has a rational position that cannot be rounded without inverting a tet");
    }
    new_index[v] = static_cast<Index>(out.positions.size());
    out.positions.push_back(mesh.position(v).approx);
  }
  out.tets.reserve(mesh.num_tets());
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    Tet tet = mesh.tet(t);
    for (Index& v : tet) v = new_index[v];
    out.tets.push_back(tet);
  }
  return out;
}

}  // namespace mr::tetmesh
