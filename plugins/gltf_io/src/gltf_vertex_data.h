#pragma once
// What a glTF writer needs from a soup: attributes made valid for glTF (unit
// normals, finite texture coordinates, colours in [0,1]), float arrays, and
// the faces grouped by region.

#include <mr/core/triangle_soup.h>

#include <array>
#include <vector>

namespace mr::plugins::gltf {

/// A copy of `soup` whose attributes the Khronos validator accepts: zero or
/// non-finite normals replaced by the vertex's face normal (or +Z), others
/// normalized; non-finite texture coordinates set to 0; colours clamped.
TriangleSoup sanitized_for_gltf(const TriangleSoup& soup);

/// The vertex attribute that carries TriangleSoup::face_sources: glTF has
/// per-vertex attributes only, so each face gets vertices of its own
/// (with_own_vertices), and an application-specific name starts with "_".
/// A float: exact for face numbers up to 2^24.
inline constexpr const char* kSourceFaceAttribute = "_SOURCE_FACE";

/// `soup` with three vertices of its own per face (attributes copied).
TriangleSoup with_own_vertices(const TriangleSoup& soup);

struct FloatArrays {
  std::vector<float> positions, normals, uvs, colors;  ///< flattened, 3/3/2/4 per vertex
  std::vector<float> sources;         ///< per vertex, its face's source (with_own_vertices first)
  std::array<float, 3> min{}, max{};  ///< of the float positions as written
};

/// Positions relative to `origin` (the node's translation). Throws
/// RunError if a coordinate does not fit in a float, or a face source in a
/// float exactly.
FloatArrays float_arrays(const TriangleSoup& soup, const Vec3d& origin = Vec3d::Zero());

struct RegionGroup {
  int region = -1;  ///< -1: no region, no material
  std::vector<Triangle> triangles;
};

/// Faces grouped by region id, in increasing id order (one group if no regions).
std::vector<RegionGroup> group_by_region(const TriangleSoup& soup);

/// The part of `soup` that `triangles` use, with vertices renumbered in order of first use.
TriangleSoup sub_soup(const TriangleSoup& soup, const std::vector<Triangle>& triangles);

}  // namespace mr::plugins::gltf
