#pragma once
// A triangle soup: the most permissive surface representation. It holds any
// input as it was read: non-manifold edges, duplicate and zero-area faces,
// faces with repeated vertex indices and isolated vertices are all kept.

#include <mr/core/material.h>
#include <mr/core/types.h>

#include <array>
#include <string>
#include <vector>

namespace mr {

struct TriangleSoup {
  std::vector<Vec3d> positions;
  std::vector<Triangle> triangles;

  // Optional per-vertex attributes: each is empty or has positions.size() entries.
  std::vector<Vec3f> normals;
  std::vector<Vec2f> uvs;
  std::vector<Vec4f> colors;  ///< RGBA in [0,1]

  // Optional per-face region (material) id: empty or triangles.size() entries.
  std::vector<std::int32_t> face_regions;
  /// Optional names of regions, indexed by region id (e.g. glTF material names).
  std::vector<std::string> region_names;
  /// Optional materials, indexed by region id like region_names (glTF), and
  /// the images their textures use.
  std::vector<Material> materials;
  std::vector<EncodedImage> images;
  /// Optional per-face source: the face of another mesh this one came from
  /// (meshrepair's provenance; -1: none), empty or triangles.size() entries.
  /// glTF stores it as the _SOURCE_FACE vertex attribute.
  std::vector<std::int64_t> face_sources;

  std::size_t num_vertices() const { return positions.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  bool has_normals() const { return !normals.empty(); }
  bool has_uvs() const { return !uvs.empty(); }
  bool has_colors() const { return !colors.empty(); }
  bool has_face_regions() const { return !face_regions.empty(); }
  bool has_face_sources() const { return !face_sources.empty(); }
  /// The positions of the corners of triangle f.
  std::array<Vec3d, 3> corners(std::size_t f) const {
    const Triangle& t = triangles[f];
    return {positions[t[0]], positions[t[1]], positions[t[2]]};
  }

  /// Appends `other`, offsetting its indices. Attributes present in only one
  /// of the two soups are dropped (a soup carries an attribute for all or none).
  /// Materials are this soup's, or other's when this one has none. Face
  /// sources of a soup without them are -1.
  void append(const TriangleSoup& other);
};

/// Returns a description of the first structural inconsistency (index out of
/// range, attribute array of the wrong size, non-finite coordinate), or an
/// empty string when the soup is consistent.
std::string find_soup_inconsistency(const TriangleSoup& soup);

/// Axis-aligned bounding box of every vertex, referenced or not; a box at
/// the origin for an empty soup.
Eigen::AlignedBox3d bounding_box(const TriangleSoup& soup);

/// A triangle's corner coordinates, corners in lexicographic order: the same
/// for the triangle met in any rotation or orientation (a key for a face by
/// its positions).
std::array<double, 9> sorted_corner_coordinates(const std::array<Vec3d, 3>& corners);

/// Axis-aligned bounding box of the corners of the triangles (unused
/// vertices left out); empty if there is no triangle.
Eigen::AlignedBox3d used_bounding_box(const TriangleSoup& soup);

/// Axis-aligned bounding box diagonal length of the referenced and unreferenced
/// vertices alike; 0 for an empty soup.
double bounding_box_diagonal(const TriangleSoup& soup);

}  // namespace mr
