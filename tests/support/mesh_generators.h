#pragma once
// Parametric test meshes shared by the tests and the benchmarks (bench/ has
// this folder on its include path). Header only, no dependency beyond mr_core.

#include <mr/core/triangle_soup.h>

#include <algorithm>
#include <map>
#include <random>
#include <utility>
#include <vector>

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

/// Splits every face of `soup` into four, new vertices at edge midpoints
/// pushed onto the unit sphere, `levels` times.
inline void subdivide_onto_unit_sphere(TriangleSoup& soup, int levels) {
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<Index, Index>, Index> middle;
    auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      const auto [it, added] = middle.emplace(key, Index(soup.positions.size()));
      if (added) soup.positions.push_back((soup.positions[a] + soup.positions[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : soup.triangles) {
      const Index ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
    }
    soup.triangles = std::move(finer);
  }
}

/// A sphere of radius `radius` about the origin: an octahedron subdivided
/// `subdivisions` times (8 * 4^n faces), new points pushed onto the sphere.
inline TriangleSoup sphere(double radius, int subdivisions) {
  TriangleSoup soup;
  soup.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  soup.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  subdivide_onto_unit_sphere(soup, subdivisions);
  for (Vec3d& p : soup.positions) p *= radius;
  return soup;
}

/// Every vertex moved by `amount` in a random direction (seeded).
inline TriangleSoup jittered(TriangleSoup soup, double amount, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  for (Vec3d& p : soup.positions)
    p += amount * Vec3d(normal(random), normal(random), normal(random)).normalized();
  return soup;
}

}  // namespace mr::test
