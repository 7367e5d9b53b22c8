#pragma once
// Merging of vertices with bit-identical coordinates.

#include <mr/core/triangle_soup.h>

namespace mr::simplify {

/// Positions and triangles of `soup` with bit-identical vertices merged; each
/// vertex keeps the index of its first occurrence order. Attributes are dropped.
TriangleSoup weld_identical_vertices(const TriangleSoup& soup);

}  // namespace mr::simplify
