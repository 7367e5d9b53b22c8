#pragma once
// Building a TriangleSoup straight from what a reader parses, without a
// halfedge structure, so that no face is ever lost or duplicated: polygons
// are fan-triangulated, triangle strips unrolled, named regions numbered in
// order of first use, and corner positions welded into shared vertices.

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mr::plugins::stl_obj_off_ply {

/// Appends the fan (p0, pi, pi+1) of a polygon with at least 3 corners.
void append_fan(std::vector<Triangle>& triangles, std::span<const Index> polygon);

/// Appends the triangles of one strip (no restart markers inside), alternating
/// orientation so that every triangle has the orientation of the first.
/// Triangles with a repeated index are the strip's stitching, not faces, and
/// are skipped. Returns the number of triangles appended.
std::size_t append_strip(std::vector<Triangle>& triangles, std::span<const Index> strip);

/// Region (material, group, solid) names numbered in order of first use.
class RegionTable {
 public:
  std::int32_t id_of(std::string_view name);
  const std::vector<std::string>& names() const { return names_; }

 private:
  std::vector<std::string> names_;
  std::unordered_map<std::string, std::int32_t> ids_;
};

/// Merges corners with bit-identical positions into one vertex each, numbered
/// in order of first appearance. `corners` holds 3 corners per triangle.
/// Returns positions and triangles; attributes are left empty.
TriangleSoup weld_triangle_corners(const std::vector<Vec3d>& corners);

/// The same for float corners stored in fixed-size records (binary STL
/// facets): record i holds triangle i's three corners as 9 floats at `offset`.
TriangleSoup weld_float_corners(const char* records, std::size_t count, std::size_t record_size,
                                std::size_t offset);

}  // namespace mr::plugins::stl_obj_off_ply
