// Timing of a 1M-triangle GLB and Draco GLB, write and read. Hidden ("[.]"):
// run it by hand with  mr_tests "[gltf][perf]".

#include "test_support.h"

#include <mr/io/mesh_io.h>
#include <mr/plugins/gltf_formats.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

using namespace mr;

namespace {

// A wavy grid of n x n quads (2 n^2 triangles) with normals.
TriangleSoup wavy_grid(int n) {
  TriangleSoup soup;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = i / double(n), y = j / double(n);
      soup.positions.emplace_back(x, y, 0.05 * std::sin(20 * x) * std::cos(20 * y));
      soup.normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  const auto at = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      soup.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      soup.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return soup;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TEST_CASE("1M-triangle GLB and Draco GLB write and read times", "[.][gltf][perf]") {
  io::Registry registry;
  plugins::register_gltf_formats(registry);
  const TriangleSoup grid = wavy_grid(708);  // 1,002,528 triangles
  test::TempDir dir("gltf_perf");
  for (bool draco : {false, true}) {
    io::WriteOptions options;
    options.draco.compress_gltf = draco;
    const auto path = dir / (draco ? "grid_draco.glb" : "grid.glb");
    auto start = std::chrono::steady_clock::now();
    io::write_surface(registry, grid, path, options);
    const double write_s = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const TriangleSoup back = io::read_surface(registry, path);
    const double read_s = seconds_since(start);
    CHECK(back.num_triangles() == grid.num_triangles());
    WARN((draco ? "Draco GLB" : "GLB") << ": " << grid.num_triangles() << " triangles, "
                                       << std::filesystem::file_size(path) / 1e6 << " MB, write " << write_s
                                       << " s, read " << read_s << " s");
  }
}
