#pragma once
// Parametric test meshes shared by the tests and the benchmarks (bench/ has
// this folder on its include path). Header only, no dependency beyond mr_core.

#include <mr/core/triangle_soup.h>

namespace mr::test {

/// A closed torus-like grid: nu x nv vertices at position(i, j) (i around the
/// main circle, j around the tube; vertex index i * nv + j), each grid cell
/// split into two triangles. 2 * nu * nv triangles, welded and manifold.
template <class Position>
TriangleSoup torus_grid(int nu, int nv, const Position& position) {
  TriangleSoup soup;
  soup.positions.reserve(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) soup.positions.push_back(position(i, j));
  const auto at = [&](int i, int j) { return static_cast<Index>((i % nu) * nv + (j % nv)); };
  soup.triangles.reserve(2 * soup.positions.size());
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      soup.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      soup.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return soup;
}

}  // namespace mr::test
