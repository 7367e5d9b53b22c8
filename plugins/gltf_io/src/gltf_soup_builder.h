#pragma once
// Collects the primitives of a glTF scene into one soup: vertices moved to
// world coordinates, winding kept outward, attributes kept consistent across
// primitives (see gltf_reader.h for the policy), materials turned into regions.

#include <mr/core/triangle_soup.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mr::plugins::gltf {

/// A node's world transform, with what is derived from it once.
struct Transform {
  explicit Transform(const Eigen::Matrix4d& world);
  Eigen::Matrix3d linear;
  Eigen::Vector3d translation;
  Eigen::Matrix3d normal_matrix;  ///< inverse transpose of `linear`, up to a positive factor
  bool flips_winding = false;     ///< negative determinant: a mirror
};

class SoupBuilder {
 public:
  /// `buffer_bytes`: the total size of the file's buffers, which bounds how
  /// many vertices instancing may create (see add_vertices).
  SoupBuilder(std::string path, std::size_t buffer_bytes);

  /// Appends the vertices and attributes of `piece` (its triangles are
  /// ignored), transformed; returns the index of its first vertex.
  Index add_vertices(const TriangleSoup& piece, const Transform& transform);

  /// Appends triangles whose indices are relative to `base`; `material` -1 = none.
  /// `sources`: one face source per triangle (_SOURCE_FACE), or empty.
  void add_triangles(const std::vector<Triangle>& triangles, Index base, int material,
                     const Transform& transform, const std::vector<std::int64_t>& sources = {});

  TriangleSoup finish(const std::vector<std::string>& material_names);

 private:
  void check_growth(std::size_t vertices, std::size_t triangles) const;

  std::string path_;
  std::size_t limit_;
  TriangleSoup soup_;
  bool all_have_normals_ = true;
  bool any_has_uvs_ = false;
  bool any_has_colors_ = false;
  std::vector<int> face_materials_;
  std::vector<std::int64_t> face_sources_;  ///< -1 for faces of primitives without them
  bool any_has_sources_ = false;
};

}  // namespace mr::plugins::gltf
