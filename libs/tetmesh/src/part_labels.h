#pragma once
// Labels of the kept tets by the input part they lie in, for multi-material
// simulations: a part is a face region of the input (glTF material, OBJ
// group or material), a connected component, or a winding-number level.

#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/mesh.h>
#include <mr/tetmesh/options.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace mr::tetmesh::detail {

/// More parts than this cannot be told apart (each costs a winding-number
/// tree and a query per region of tets).
inline constexpr std::size_t kMaxLabelledParts = 1024;

struct PartLabels {
  std::vector<std::int32_t> labels;           ///< per tet slot; 0 where keep[t] == 0
  std::map<std::int32_t, std::string> names;  ///< for labels that have one
};

/// Labels every tet with keep[t] != 0. Tets connected through faces that
/// are not tracked surface get one label, decided at the centroid of their
/// largest tet: that of the innermost part containing it (winding number
/// above 1/2, |w| under WindingRule::absolute; least enclosed volume), or
/// where none does, of the part whose winding number is largest.
/// TetLabels::winding labels by the whole input's winding number rounded
/// instead (at least 1).
/// Throws RunError when an explicit mode finds more than kMaxLabelledParts
/// parts; TetLabels::automatic then falls back to none.
PartLabels part_labels(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input,
                       TetLabels mode, WindingRule rule);

}  // namespace mr::tetmesh::detail
