#pragma once
// How a TetMesh maps onto MSH entities: one entity per distinct label (per
// dimension), and element blocks that follow runs of equal labels so that
// elements keep their order through a write and a read.

#include <mr/core/tet_mesh.h>

#include <array>
#include <cstdint>
#include <vector>

namespace mr::plugins::tet {

struct MshEntity {
  std::int32_t tag = 1;
  std::int32_t label = 0;
  bool has_physical = false;  ///< false when the mesh has no labels of that kind
};

struct MshBlock {
  std::int32_t entity_tag = 1;
  std::int32_t label = 0;
  std::size_t begin = 0, end = 0;  ///< element range [begin, end)
};

struct MshDimension {
  std::vector<MshEntity> entities;  ///< in order of first use
  std::vector<MshBlock> blocks;
};

struct MshLayout {
  MshDimension volumes;
  MshDimension surfaces;
  std::array<double, 6> bounding_box{};  ///< min x y z, max x y z
  int node_entity_dim = 3;               ///< entity that holds all nodes
  std::int32_t node_entity_tag = 1;
};

MshLayout make_msh_layout(const TetMesh& mesh);

}  // namespace mr::plugins::tet
