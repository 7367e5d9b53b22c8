#include "msh_content.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <unordered_map>

namespace mr::plugins::tet {
namespace {

constexpr Index kNoNode = std::numeric_limits<Index>::max();

// Node tag -> index. Contiguous tags (the usual case) need no table; a dense
// table is used only when its size is bounded by a small multiple of the node
// count (itself bounded by the file size), a hash map otherwise.
class NodeIndex {
 public:
  NodeIndex(const std::vector<std::uint64_t>& tags, const std::string& path) {
    if (tags.size() >= kNoNode)
      throw InputError(path, "too many nodes (" + std::to_string(tags.size()) + ")");
    if (tags.empty()) return;
    first_ = tags.front();
    count_ = tags.size();
    contiguous_ = true;
    for (std::size_t i = 0; i < tags.size() && contiguous_; ++i) contiguous_ = tags[i] - first_ == i;
    if (contiguous_ && tags.back() >= first_) return;
    contiguous_ = false;
    const auto [lo, hi] = std::minmax_element(tags.begin(), tags.end());
    first_ = *lo;
    if (*hi - *lo < 4 * tags.size() + 1024) {
      dense_.assign(*hi - *lo + 1, kNoNode);
      for (std::size_t i = 0; i < tags.size(); ++i) insert(dense_[tags[i] - first_], i, tags[i], path);
    } else {
      sparse_.reserve(tags.size());
      for (std::size_t i = 0; i < tags.size(); ++i)
        insert(sparse_.try_emplace(tags[i], kNoNode).first->second, i, tags[i], path);
    }
  }

  std::optional<Index> find(std::uint64_t tag) const {
    if (contiguous_) {
      if (tag - first_ < count_) return static_cast<Index>(tag - first_);
      return std::nullopt;
    }
    if (!dense_.empty()) {
      if (tag - first_ < dense_.size() && dense_[tag - first_] != kNoNode) return dense_[tag - first_];
      return std::nullopt;
    }
    const auto it = sparse_.find(tag);
    if (it == sparse_.end()) return std::nullopt;
    return it->second;
  }

 private:
  void insert(Index& slot, std::size_t index, std::uint64_t tag, const std::string& path) {
    if (slot != kNoNode) throw InputError(path, "node tag " + std::to_string(tag) + " is defined twice");
    slot = static_cast<Index>(index);
  }

  bool contiguous_ = true;
  std::uint64_t first_ = 0;
  std::size_t count_ = 0;
  std::vector<Index> dense_;
  std::unordered_map<std::uint64_t, Index> sparse_;
};

template <std::size_t N>
std::vector<std::array<Index, N>> resolve(const std::vector<std::array<std::uint64_t, N>>& cells,
                                          const NodeIndex& index, const char* what, const std::string& path) {
  std::vector<std::array<Index, N>> resolved(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (std::size_t k = 0; k < N; ++k) {
      const std::optional<Index> node = index.find(cells[c][k]);
      if (!node)
        throw InputError(path, std::string(what) + " " + std::to_string(c) + " refers to node tag " +
                                   std::to_string(cells[c][k]) + ", which no $Nodes section defines");
      resolved[c][k] = *node;
    }
  return resolved;
}

// One value per position, NaN for the nodes the field leaves out.
std::vector<double> node_values(const MshNodeField& field, const NodeIndex& index, std::size_t nodes,
                                const std::string& path) {
  std::vector<double> values(nodes, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < field.tags.size(); ++i) {
    const std::optional<Index> node = index.find(field.tags[i]);
    if (!node)
      throw InputError(path, "$NodeData '" + field.name + "' gives a value for node tag " +
                                 std::to_string(field.tags[i]) + ", which no $Nodes section defines");
    values[*node] = field.values[i];
  }
  return values;
}

}  // namespace

int msh_element_node_count(int type) {
  // gmsh's element type numbers (GmshDefines.h). 32 and 33 changed meaning
  // between gmsh versions and 34, 35, 67-70 have no fixed size: all rejected.
  static constexpr int kCounts[] = {
      0,   2,   3,   4,   4,  8,  6,  5,  3,  6,  9,   10,  27,  18,  14,  1,   8,   20,  15,  13,
      9,   10,  12,  15,  15, 21, 4,  5,  6,  20, 35,  56,  0,   0,   0,   0,   16,  25,  36,  12,
      16,  20,  28,  36,  45, 55, 66, 49, 64, 81, 100, 121, 18,  21,  24,  27,  30,  24,  28,  32,
      36,  40,  7,   8,   9,  10, 11, 0,  0,  0,  0,   84,  120, 165, 220, 286, 0,   0,   0,   74,
      100, 130, 164, 202, 1,  1,  1,  1,  1,  1,  40,  75,  64,  125, 216, 343, 512, 729, 1000};
  if (type < 0 || type >= static_cast<int>(std::size(kCounts))) return 0;
  return kCounts[type];
}

void MshContent::add_element(int type, const std::uint64_t* nodes, std::int32_t label) {
  if (type == 4 || type == 11) {
    tets.push_back({nodes[0], nodes[1], nodes[2], nodes[3]});
    tet_labels.push_back(label);
  } else if (type == 2 || type == 9) {
    triangles.push_back({nodes[0], nodes[1], nodes[2]});
    triangle_labels.push_back(label);
  }
}

TetMesh assemble_tet_mesh(MshContent&& content, const std::string& path) {
  const NodeIndex index(content.node_tags, path);
  TetMesh mesh;
  mesh.tets = resolve(content.tets, index, "tet", path);
  mesh.faces = resolve(content.triangles, index, "triangle", path);
  mesh.positions = std::move(content.positions);
  mesh.tet_labels = std::move(content.tet_labels);
  mesh.face_labels = std::move(content.triangle_labels);
  mesh.tet_label_names = std::move(content.tet_label_names);
  for (const MshNodeField& field : content.node_fields)
    mesh.node_fields[field.name] = node_values(field, index, mesh.positions.size(), path);
  return mesh;
}

}  // namespace mr::plugins::tet
