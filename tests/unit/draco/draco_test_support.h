#pragma once
// Models and comparisons for the Draco tests. Draco reorders vertices and
// faces and rotates corners, so meshes are compared through a vertex match.

#include "test_support.h"

#include <mr/core/triangle_soup.h>

#include <string>
#include <vector>

namespace mr::draco_test {

/// test::cube_soup() with a normal, uv and colour per vertex.
TriangleSoup cube_with_attributes();

/// nx by ny quads on a wavy height field, two triangles each; `jitter` moves
/// vertices off the lattice (fraction of the spacing) so quantization shows.
TriangleSoup make_grid(int nx, int ny, double jitter);

/// Largest position error of `bits`-bit Draco quantization over the soup's bounding box.
double position_bound(const TriangleSoup& soup, int bits);
/// Largest error quantizing values spanning `range` with `bits` bits.
double value_bound(double range, int bits);

struct VertexMatch {
  std::vector<Index> original;  ///< nearest original vertex of each decoded vertex
  double max_position_error = 0;
};
VertexMatch match_vertices(const TriangleSoup& original, const TriangleSoup& decoded);

/// The decoded triangles in original vertex indices.
std::vector<Triangle> mapped_triangles(const TriangleSoup& decoded, const VertexMatch& match);

/// Each triangle rotated to its smallest rotation (orientation kept), sorted.
std::vector<Triangle> canonical_triangles(std::vector<Triangle> triangles);
/// Same, each with its region appended.
std::vector<std::array<std::int64_t, 4>> canonical_region_triangles(const std::vector<Triangle>& triangles,
                                                                    const std::vector<std::int32_t>& regions);

/// The full path of an executable found on PATH, or "" if there is none.
std::string find_on_path(const std::string& name);

}  // namespace mr::draco_test
