#include <mr/core/tet_mesh.h>

#include <string>

namespace mr {

std::string find_tet_mesh_inconsistency(const TetMesh& mesh) {
  const std::size_t n = mesh.positions.size();
  for (std::size_t v = 0; v < n; ++v)
    if (!mesh.positions[v].allFinite())
      return "node " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)";
  auto check_indices = [n](const auto& cells, const char* what) -> std::string {
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (Index i : cells[c])
        if (i >= n)
          return std::string(what) + " " + std::to_string(c) + " refers to node " + std::to_string(i) +
                 " but there are only " + std::to_string(n) + " nodes";
    return {};
  };
  if (auto problem = check_indices(mesh.tets, "tet"); !problem.empty()) return problem;
  if (auto problem = check_indices(mesh.faces, "triangle"); !problem.empty()) return problem;
  if (!mesh.tet_labels.empty() && mesh.tet_labels.size() != mesh.tets.size())
    return "tet labels do not match the number of tets";
  if (!mesh.face_labels.empty() && mesh.face_labels.size() != mesh.faces.size())
    return "triangle labels do not match the number of triangles";
  for (const auto& [name, values] : mesh.node_fields)
    if (values.size() != n) return "node field '" + name + "' does not have one value per node";
  return {};
}

}  // namespace mr
