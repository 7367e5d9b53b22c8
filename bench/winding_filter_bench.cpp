// Winding numbers at the centroids of a tet mesh with respect to a surface,
// as the tetrahedralizer's filter asks them when the tracked surface is not
// closed: `winding_filter_bench SURFACE TETS [beta]`, e.g. the files written
// by `tetrahedralize IN tets.mesh --no-filter --max-passes 0 --surface surface.obj`.
// Prints the build and query times and the queries per second.

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/winding_number/winding_number.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace {

template <class F>
double seconds(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: winding_filter_bench SURFACE TETS [beta]\n");
    return 2;
  }
  const mr::io::Registry registry = mr::io::make_default_registry();
  const mr::TriangleSoup surface = mr::io::read_surface(registry, argv[1]);
  const mr::TetMesh tets = mr::io::read_volume(registry, argv[2]);
  mr::WindingNumberOptions options;
  if (argc > 3) options.beta = std::stod(argv[3]);

  std::vector<mr::Vec3d> centroids;
  centroids.reserve(tets.tets.size());
  for (const mr::Tet& t : tets.tets) {
    centroids.push_back(
        0.25 * (tets.positions[t[0]] + tets.positions[t[1]] + tets.positions[t[2]] + tets.positions[t[3]]));
  }
  std::optional<mr::WindingNumberTree> tree;
  const double build = seconds([&] { tree.emplace(surface, options); });
  std::vector<double> values;
  const double query = seconds([&] { values = tree->evaluate(centroids); });
  std::size_t inside = 0;
  for (double w : values) inside += std::abs(w) > 0.5;
  std::printf("faces %zu nodes %zu tets %zu build %.3f s queries %.3f s (%.0f/s) inside %zu\n",
              tree->num_triangles(), tree->num_nodes(), centroids.size(), build, query,
              static_cast<double>(centroids.size()) / query, inside);
  return 0;
}
