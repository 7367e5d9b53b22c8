#include "gltf_soup_builder.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <limits>

namespace mr::plugins::gltf {
namespace {

const Vec4f opaque_white(1.0f, 1.0f, 1.0f, 1.0f);

// Instancing lets a small file describe a huge scene: we accept up to this
// many vertices (and triangles) per byte of buffer data, and at least 16M.
constexpr std::size_t elements_per_buffer_byte = 4;
constexpr std::size_t min_element_limit = std::size_t{1} << 24;

}  // namespace

Transform::Transform(const Eigen::Matrix4d& world)
    : linear(world.topLeftCorner<3, 3>()), translation(world.topRightCorner<3, 1>()) {
  // Cofactor matrix = det * inverse transpose; defined even for a singular
  // matrix, and its sign is corrected so normals keep their side.
  const Eigen::Vector3d a = linear.col(0), b = linear.col(1), c = linear.col(2);
  normal_matrix.col(0) = b.cross(c);
  normal_matrix.col(1) = c.cross(a);
  normal_matrix.col(2) = a.cross(b);
  const double det = linear.determinant();
  flips_winding = det < 0;
  if (flips_winding) normal_matrix = -normal_matrix;
}

SoupBuilder::SoupBuilder(std::string path, std::size_t buffer_bytes)
    : path_(std::move(path)),
      limit_(std::min<std::size_t>(std::max(min_element_limit, buffer_bytes * elements_per_buffer_byte),
                                   std::numeric_limits<Index>::max())) {}

void SoupBuilder::check_growth(std::size_t vertices, std::size_t triangles) const {
  if (vertices > limit_ - std::min(limit_, soup_.positions.size()) ||
      triangles > limit_ - std::min(limit_, soup_.triangles.size()))
    throw InputError(path_,
                     "the scene instances its meshes into more than " + std::to_string(limit_) +
                         " vertices or triangles, far more than the file's data; refusing to expand it");
}

Index SoupBuilder::add_vertices(const TriangleSoup& piece, const Transform& transform) {
  check_growth(piece.positions.size(), 0);
  const std::size_t before = soup_.positions.size();
  const std::size_t after = before + piece.positions.size();
  for (const Vec3d& p : piece.positions)
    soup_.positions.push_back(transform.linear * p + transform.translation);

  all_have_normals_ = all_have_normals_ && piece.has_normals();
  if (all_have_normals_) {
    for (const Vec3f& n : piece.normals) {
      const Eigen::Vector3d world = transform.normal_matrix * n.cast<double>();
      const double length = world.norm();
      soup_.normals.push_back((length > 0 ? Eigen::Vector3d(world / length) : world).cast<float>());
    }
  } else {
    soup_.normals.clear();
  }
  // A primitive without texture coordinates gets (0, 0): its material
  // samples no texture through them (else the file is invalid), while the
  // others keep theirs (CesiumMilkTruck's textured body beside its
  // untextured windows).
  if (piece.has_uvs() && !any_has_uvs_) soup_.uvs.assign(before, Vec2f::Zero());
  any_has_uvs_ = any_has_uvs_ || piece.has_uvs();
  if (piece.has_uvs())
    soup_.uvs.insert(soup_.uvs.end(), piece.uvs.begin(), piece.uvs.end());
  else if (any_has_uvs_)
    soup_.uvs.resize(after, Vec2f::Zero());

  if (piece.has_colors() && !any_has_colors_) soup_.colors.assign(before, opaque_white);
  any_has_colors_ = any_has_colors_ || piece.has_colors();
  if (piece.has_colors())
    soup_.colors.insert(soup_.colors.end(), piece.colors.begin(), piece.colors.end());
  else if (any_has_colors_)
    soup_.colors.resize(after, opaque_white);
  return static_cast<Index>(before);
}

void SoupBuilder::add_triangles(const std::vector<Triangle>& triangles, Index base, int material,
                                const Transform& transform, const std::vector<std::int64_t>& sources) {
  check_growth(0, triangles.size());
  for (Triangle t : triangles) {
    for (Index& v : t) v += base;
    if (transform.flips_winding) std::swap(t[1], t[2]);
    soup_.triangles.push_back(t);
  }
  face_materials_.insert(face_materials_.end(), triangles.size(), material);
  any_has_sources_ = any_has_sources_ || !sources.empty();
  if (sources.empty())
    face_sources_.insert(face_sources_.end(), triangles.size(), -1);
  else
    face_sources_.insert(face_sources_.end(), sources.begin(), sources.end());
}

TriangleSoup SoupBuilder::finish(const std::vector<std::string>& material_names) {
  const bool any_material =
      std::any_of(face_materials_.begin(), face_materials_.end(), [](int m) { return m >= 0; });
  if (any_material) {
    const bool any_without =
        std::any_of(face_materials_.begin(), face_materials_.end(), [](int m) { return m < 0; });
    soup_.region_names = material_names;
    const auto default_region = static_cast<std::int32_t>(material_names.size());
    if (any_without) soup_.region_names.push_back("default");
    soup_.face_regions.reserve(face_materials_.size());
    for (int m : face_materials_) soup_.face_regions.push_back(m >= 0 ? m : default_region);
  }
  if (any_has_sources_) soup_.face_sources = std::move(face_sources_);
  return std::move(soup_);
}

}  // namespace mr::plugins::gltf
