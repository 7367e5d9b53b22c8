#include <mr/tetmesh/sizing_field.h>

#include <mr/core/errors.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace mr::tetmesh {
namespace {

Vec3d box_min(const TetMesh& mesh, const Tet& t) {
  Vec3d lo = mesh.positions[t[0]];
  for (const Index v : t) lo = lo.cwiseMin(mesh.positions[v]);
  return lo;
}

Vec3d box_max(const TetMesh& mesh, const Tet& t) {
  Vec3d hi = mesh.positions[t[0]];
  for (const Index v : t) hi = hi.cwiseMax(mesh.positions[v]);
  return hi;
}

Eigen::AlignedBox3d bounds(const TetMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Vec3d& p : mesh.positions) box.extend(p);
  return box;
}

// A cell about twice the mean tet's size: a few tets per cell.
double cell_size(const Eigen::AlignedBox3d& box, std::size_t tets) {
  const Vec3d extent = box.sizes().cwiseMax(Vec3d::Constant(1e-300));
  const double per_tet = extent.prod() / double(std::max<std::size_t>(tets, 1));
  const double size = 2 * std::cbrt(per_tet);
  return std::isfinite(size) && size > 0 ? size : extent.maxCoeff();
}

// Barycentric coordinates of p in tet t (any orientation); empty for a flat tet.
std::optional<std::array<double, 4>> barycentric(const TetMesh& mesh, const Tet& t, const Vec3d& p) {
  const Vec3d& a = mesh.positions[t[0]];
  const Vec3d ab = mesh.positions[t[1]] - a, ac = mesh.positions[t[2]] - a, ad = mesh.positions[t[3]] - a;
  const double volume = ab.dot(ac.cross(ad));
  if (volume == 0 || !std::isfinite(volume)) return std::nullopt;
  const Vec3d ap = p - a;
  const double b = ap.dot(ac.cross(ad)) / volume;
  const double c = ab.dot(ap.cross(ad)) / volume;
  const double d = ab.dot(ac.cross(ap)) / volume;
  return std::array<double, 4>{1 - b - c - d, b, c, d};
}

}  // namespace

TetMeshField::TetMeshField(TetMesh mesh, std::vector<double> values)
    : mesh_(std::move(mesh)), values_(std::move(values)) {
  if (mesh_.tets.empty() || values_.size() != mesh_.positions.size())
    throw UsageError("TetMeshField: a mesh with tets and one value per vertex is needed");
  // From a cell below the lowest corner: positions below the grid's origin
  // all land in its first layer of cells.
  const Eigen::AlignedBox3d box = bounds(mesh_);
  const double cell = cell_size(box, mesh_.tets.size());
  grid_ = spatial::BoxGrid(box.min() - Vec3d::Constant(cell), cell);
  for (std::size_t t = 0; t < mesh_.tets.size(); ++t)
    grid_.insert(std::uint32_t(t), box_min(mesh_, mesh_.tets[t]), box_max(mesh_, mesh_.tets[t]));
}

// Interpolation, not a topological decision: a point on a shared face or
// just outside by rounding takes the tet it is least outside of (within a
// relative 1e-9), the first such tet in index order.
double TetMeshField::at(const Vec3d& p) const {
  constexpr double kSlack = 1e-9;
  // Sampled at every vertex, from every thread: one buffer per thread.
  thread_local std::vector<std::uint32_t> candidates;
  grid_.query(p, p, candidates);
  double best_margin = -kSlack, value = std::numeric_limits<double>::quiet_NaN();
  for (const std::uint32_t t : candidates) {
    const Tet& tet = mesh_.tets[t];
    const auto weights = barycentric(mesh_, tet, p);
    if (!weights) continue;
    const double margin = *std::min_element(weights->begin(), weights->end());
    if (margin <= best_margin) continue;
    best_margin = margin;
    value = 0;
    for (int k = 0; k < 4; ++k) value += (*weights)[k] * values_[tet[k]];
    if (margin >= 0) break;
  }
  return value;
}

std::shared_ptr<const ScalarField> sizing_from_tet_mesh(TetMesh mesh, const std::string& path) {
  if (mesh.tets.empty()) throw InputError(path, "a sizing field needs a tet mesh; the file has no tets");
  auto field = mesh.node_fields.find("values");
  if (field == mesh.node_fields.end() && mesh.node_fields.size() == 1) field = mesh.node_fields.begin();
  if (field == mesh.node_fields.end())
    throw InputError(path,
                     mesh.node_fields.empty()
                         ? "a sizing field needs one value per node ($NodeData \"values\"); the file has none"
                         : "the file has several node fields and none is named \"values\"");
  std::vector<double> values = std::move(field->second);
  for (std::size_t v = 0; v < values.size(); ++v) {
    if (std::isnan(values[v]) || (values[v] > 0 && std::isfinite(values[v]))) continue;
    throw InputError(path, "sizing value " + std::to_string(values[v]) + " at node " + std::to_string(v + 1) +
                               " is not a positive length");
  }
  mesh.node_fields.clear();
  return std::make_shared<TetMeshField>(std::move(mesh), std::move(values));
}

}  // namespace mr::tetmesh
