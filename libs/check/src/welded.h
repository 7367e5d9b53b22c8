#pragma once
// Triangles re-indexed so that bit-identical positions share one index.

#include <mr/core/triangle_soup.h>

#include <vector>

namespace mr::check::detail {

struct Welded {
  std::vector<Vec3d> positions;     ///< unique positions
  std::vector<Triangle> triangles;  ///< same order as the soup's
};

Welded weld_identical(const TriangleSoup& soup);

}  // namespace mr::check::detail
