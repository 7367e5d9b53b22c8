#pragma once
// What the MSH readers collect before node tags are resolved: elements refer
// to nodes by tag, and tags may be sparse, huge (64-bit in MSH 4.1) or appear
// after the elements that use them, so resolution waits for the whole file.

#include <mr/core/tet_mesh.h>

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mr::plugins::tet {

/// Nodes per element of gmsh element type `type`; 0 for unknown types and
/// for types whose node count is not fixed (polygons, polyhedra).
int msh_element_node_count(int type);

/// A one-component $NodeData section, by node tag.
struct MshNodeField {
  std::string name;
  std::vector<std::uint64_t> tags;
  std::vector<double> values;
};

struct MshContent {
  std::vector<Vec3d> positions;
  std::vector<std::uint64_t> node_tags;  ///< one per position
  std::vector<std::array<std::uint64_t, 4>> tets;
  std::vector<std::int32_t> tet_labels;
  std::vector<std::array<std::uint64_t, 3>> triangles;
  std::vector<std::int32_t> triangle_labels;
  std::map<std::int32_t, std::string> tet_label_names;
  std::vector<MshNodeField> node_fields;  ///< in file order; a later one of a name wins

  /// Keeps tets (type 4; corners of type 11) and triangles (type 2; corners
  /// of type 9); other types are skipped. `nodes` holds the element's first
  /// min(4, node count) node tags.
  void add_element(int type, const std::uint64_t* nodes, std::int32_t label);
};

/// Resolves node tags to indices. Throws InputError naming `path` for a node
/// tag defined twice or an element or node value that refers to an
/// undefined node. Tets are
/// kept as written, even when negatively oriented: the orientation contract
/// is checked by the caller, not repaired silently here.
TetMesh assemble_tet_mesh(MshContent&& content, const std::string& path);

}  // namespace mr::plugins::tet
