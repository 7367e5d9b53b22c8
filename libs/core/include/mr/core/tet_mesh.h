#pragma once
// A tetrahedral mesh: positions, tets (positively oriented: orient3d > 0 in
// the convention of mr::orient3d), a label per tet, and optionally labelled
// surface triangles (boundary or interface faces carried by MSH and Medit files),
// and optionally named scalar values per vertex (MSH $NodeData).

#include <mr/core/types.h>

#include <map>
#include <string>
#include <vector>

namespace mr {

struct TetMesh {
  std::vector<Vec3d> positions;
  std::vector<Tet> tets;
  std::vector<std::int32_t> tet_labels;  ///< empty or tets.size() entries
  /// Optional names of tet labels (MSH physical names), e.g. the input's
  /// material or group names.
  std::map<std::int32_t, std::string> tet_label_names;

  std::vector<Triangle> faces;            ///< optional tagged surface triangles
  std::vector<std::int32_t> face_labels;  ///< empty or faces.size() entries

  /// Scalar node data by name (MSH $NodeData of one component, e.g. the
  /// "values" of a sizing field): positions.size() entries each, NaN where
  /// the file gives no value for a vertex.
  std::map<std::string, std::vector<double>> node_fields;

  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_tets() const { return tets.size(); }
  bool has_tet_labels() const { return !tet_labels.empty(); }
};

/// Returns a description of the first structural inconsistency or "".
std::string find_tet_mesh_inconsistency(const TetMesh& mesh);

}  // namespace mr
