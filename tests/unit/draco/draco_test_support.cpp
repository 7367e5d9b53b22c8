#include "draco_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

namespace mr::draco_test {

TriangleSoup cube_with_attributes() {
  TriangleSoup cube = test::cube_soup();
  for (const Vec3d& p : cube.positions) {
    const Vec3f centred = (p - Vec3d::Constant(0.5)).cast<float>();
    cube.normals.push_back(centred.normalized());
    cube.uvs.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    cube.colors.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()),
                             1.0f);
  }
  return cube;
}

TriangleSoup make_grid(int nx, int ny, double jitter) {
  TriangleSoup grid;
  const auto vertex = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      // A deterministic pseudo-random offset per vertex.
      const double a = std::sin(i * 12.9898 + j * 78.233) * 43758.5453;
      const double offset = jitter * (a - std::floor(a) - 0.5);
      grid.positions.emplace_back(i + offset, j - offset,
                                  3.0 * std::sin(0.2 * i) * std::cos(0.15 * j) + offset);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      grid.triangles.push_back({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1)});
      grid.triangles.push_back({vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1)});
    }
  return grid;
}

double value_bound(double range, int bits) {
  // Draco rounds to the nearest of 2^bits - 1 steps over the range; allow float rounding on top.
  return 0.5 * range / ((1 << bits) - 1) + 1e-6 * range;
}

double position_bound(const TriangleSoup& soup, int bits) {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::max()), hi = -lo;
  for (const Vec3d& p : soup.positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double range = (hi - lo).maxCoeff();  // Draco quantizes every axis over the largest extent
  const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  return std::sqrt(3.0) * value_bound(range, bits) + 1e-6 * magnitude;
}

VertexMatch match_vertices(const TriangleSoup& original, const TriangleSoup& decoded) {
  VertexMatch match;
  match.original.resize(decoded.num_vertices());
  for (std::size_t v = 0; v < decoded.num_vertices(); ++v) {
    double best = std::numeric_limits<double>::max();
    for (std::size_t o = 0; o < original.num_vertices(); ++o) {
      const double d = (decoded.positions[v] - original.positions[o]).squaredNorm();
      if (d < best) {
        best = d;
        match.original[v] = static_cast<Index>(o);
      }
    }
    match.max_position_error = std::max(match.max_position_error, std::sqrt(best));
  }
  return match;
}

std::vector<Triangle> mapped_triangles(const TriangleSoup& decoded, const VertexMatch& match) {
  std::vector<Triangle> triangles = decoded.triangles;
  for (Triangle& t : triangles)
    for (Index& v : t) v = match.original.at(v);
  return triangles;
}

namespace {
Triangle smallest_rotation(const Triangle& t) {
  return std::min({t, Triangle{t[1], t[2], t[0]}, Triangle{t[2], t[0], t[1]}});
}
}  // namespace

std::vector<Triangle> canonical_triangles(std::vector<Triangle> triangles) {
  for (Triangle& t : triangles) t = smallest_rotation(t);
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

std::vector<std::array<std::int64_t, 4>> canonical_region_triangles(
    const std::vector<Triangle>& triangles, const std::vector<std::int32_t>& regions) {
  std::vector<std::array<std::int64_t, 4>> result;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle t = smallest_rotation(triangles[f]);
    result.push_back({t[0], t[1], t[2], f < regions.size() ? regions[f] : -1});
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate.string();
  }
  return {};
}

}  // namespace mr::draco_test
