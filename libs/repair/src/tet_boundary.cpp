#include <mr/repair/tet_boundary.h>

#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/kernel/predicates.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mr::repair {
namespace {

std::int32_t label_of(const TetMesh& mesh, std::size_t tet) {
  return mesh.has_tet_labels() ? mesh.tet_labels[tet] : 0;
}

std::string label_list(const TetMesh& mesh) {
  std::vector<std::int32_t> labels = mesh.has_tet_labels() ? mesh.tet_labels : std::vector<std::int32_t>{0};
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  constexpr std::size_t kShown = 20;
  std::string text;
  for (std::size_t i = 0; i < labels.size() && i < kShown; ++i)
    text += (i ? ", " : "") + std::to_string(labels[i]);
  if (labels.size() > kShown) text += ", ... (" + std::to_string(labels.size()) + " labels)";
  return text;
}

}  // namespace

TetMesh with_positive_tets(const TetMesh& mesh, std::size_t* flipped) {
  TetMesh positive = mesh;
  std::size_t count = 0;
  for (Tet& t : positive.tets) {
    const auto& p = positive.positions;
    if (orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0) {
      std::swap(t[1], t[2]);
      ++count;
    }
  }
  if (flipped) *flipped = count;
  return positive;
}

TriangleSoup tet_mesh_boundary(const TetMesh& mesh, const BoundaryRequest& request) {
  const TetMesh positive = with_positive_tets(mesh);
  switch (request.mode) {
    case BoundaryMode::interfaces:
      return extract_interfaces(positive);
    case BoundaryMode::label: {
      bool present = false;
      for (std::size_t t = 0; t < mesh.tets.size() && !present; ++t)
        present = label_of(mesh, t) == request.label;
      if (!present)
        throw UsageError("no tet has label " + std::to_string(request.label) +
                         " (labels present: " + label_list(mesh) + ")");
      return extract_boundary(positive, [&](std::size_t t) { return label_of(mesh, t) == request.label; });
    }
    case BoundaryMode::all:
      break;
  }
  return extract_boundary(positive);
}

}  // namespace mr::repair
