#pragma once
// Merging of vertices with identical coordinates (soups read from STL, or
// written with duplicated vertices, are often not welded).

#include <mr/core/triangle_soup.h>

#include <vector>

namespace mr {

/// Positions and triangles of `soup` with vertices of equal coordinates
/// merged (bit-identical, except that -0 and +0 are one); each vertex keeps
/// the index of its first occurrence order. Attributes are dropped.
TriangleSoup weld_identical_vertices(const TriangleSoup& soup);
/// The same, also giving per vertex of `soup` its index in the result
/// (so that attributes of split vertices can follow the welded positions).
TriangleSoup weld_identical_vertices(const TriangleSoup& soup, std::vector<Index>& welded_index);

}  // namespace mr
