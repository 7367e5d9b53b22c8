#include "msh_layout.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <limits>
#include <map>
#include <string>

namespace mr::plugins::tet {
namespace {

// A label >= 0 is its own entity tag (gmsh accepts tag 0, and MSH 2 readers
// fall back to the elementary tag when the physical tag is 0); a negative
// label gets a fresh tag above the largest label.
MshDimension make_dimension(const std::vector<std::int32_t>& labels, std::size_t count) {
  MshDimension dimension;
  const bool labelled = !labels.empty();
  auto label_of = [&](std::size_t i) { return labelled ? labels[i] : 1; };
  std::int64_t next_tag = 1;
  for (std::size_t i = 0; i < count; ++i)
    next_tag = std::max<std::int64_t>(next_tag, std::int64_t(label_of(i)) + 1);
  std::map<std::int32_t, std::int32_t> tag_of_label;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int32_t label = label_of(i);
    auto [it, inserted] = tag_of_label.try_emplace(label, label);
    if (inserted) {
      if (label < 0) {
        if (next_tag > std::numeric_limits<std::int32_t>::max())
          throw RunError("MSH: no free entity tag left for label " + std::to_string(label));
        it->second = static_cast<std::int32_t>(next_tag++);
      }
      dimension.entities.push_back({it->second, label, labelled});
    }
    if (dimension.blocks.empty() || dimension.blocks.back().label != label)
      dimension.blocks.push_back({it->second, label, i, i});
    dimension.blocks.back().end = i + 1;
  }
  return dimension;
}

std::array<double, 6> bounding_box(const std::vector<Vec3d>& positions) {
  if (positions.empty()) return {};
  Vec3d lo = positions.front(), hi = positions.front();
  for (const Vec3d& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()};
}

}  // namespace

MshLayout make_msh_layout(const TetMesh& mesh) {
  MshLayout layout;
  layout.volumes = make_dimension(mesh.tet_labels, mesh.tets.size());
  layout.surfaces = make_dimension(mesh.face_labels, mesh.faces.size());
  layout.bounding_box = bounding_box(mesh.positions);
  if (!layout.volumes.entities.empty()) {
    layout.node_entity_tag = layout.volumes.entities.front().tag;
  } else if (!layout.surfaces.entities.empty()) {
    layout.node_entity_dim = 2;
    layout.node_entity_tag = layout.surfaces.entities.front().tag;
  } else if (!mesh.positions.empty()) {
    layout.volumes.entities.push_back({1, 1, false});  // nodes need an entity even without elements
  }
  return layout;
}

}  // namespace mr::plugins::tet
