// I/O throughput: writes and reads a generated 1M-triangle mesh through our
// surface formats and a ~1M-tet grid through our volume formats, and reads
// the binary STL with OpenMesh's own reader for comparison.
// Usage: io_bench [WORKDIR] [TRIANGLES]   (prints a Markdown table)

#include "mesh_generators.h"

#include <mr/core/openmesh_convert.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;

// A closed torus grid with about `triangles` triangles (welded, manifold).
mr::TriangleSoup torus(std::size_t triangles) {
  const auto rings = static_cast<int>(std::sqrt(triangles));
  const auto sides = static_cast<int>(triangles / (2 * std::size_t(rings)));
  return mr::test::torus_grid(rings, sides, [&](int i, int j) {
    const double u = 2 * M_PI * i / rings, v = 2 * M_PI * j / sides;
    const double r = 3 + std::cos(v);
    return mr::Vec3d(r * std::cos(u), r * std::sin(u), std::sin(v));
  });
}

// A Kuhn-subdivided n^3 grid of the unit cube: 6 n^3 positively oriented tets.
mr::TetMesh kuhn_grid(std::size_t n) {
  mr::TetMesh mesh;
  auto id = [&](std::size_t i, std::size_t j, std::size_t k) {
    return mr::Index((i * (n + 1) + j) * (n + 1) + k);
  };
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = 0; j <= n; ++j)
      for (std::size_t k = 0; k <= n; ++k)
        mesh.positions.emplace_back(double(i) / n, double(j) / n, double(k) / n);
  // The six tets of a cube along its 0-7 diagonal, as corner bit masks (x=1, y=2, z=4).
  const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k)
        for (const auto& tet : kuhn) {
          mr::Tet t;
          for (int c = 0; c < 4; ++c)
            t[c] = id(i + (tet[c] & 1), j + ((tet[c] >> 1) & 1), k + ((tet[c] >> 2) & 1));
          const mr::Vec3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]],
                          &d = mesh.positions[t[3]];
          if ((b - a).cross(c - a).dot(d - a) < 0) std::swap(t[1], t[2]);
          mesh.tets.push_back(t);
        }
  return mesh;
}

double seconds(const std::function<void()>& work) {
  const auto start = Clock::now();
  work();
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void row(const std::string& what, double s, const std::filesystem::path& file, std::size_t faces) {
  const double mb = double(std::filesystem::file_size(file)) / 1e6;
  std::printf("| %-34s | %8.3f | %8.1f | %9.1f | %10zu |\n", what.c_str(), s, mb, mb / s, faces);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path dir =
      argc > 1 ? argv[1] : std::filesystem::temp_directory_path() / "mr_io_bench";
  const std::size_t n = argc > 2 ? std::stoul(argv[2]) : 1000000;
  std::filesystem::create_directories(dir);
  const mr::io::Registry registry = mr::io::make_default_registry();
  const mr::TriangleSoup soup = torus(n);
  std::printf("| step | seconds | MB | MB/s | faces or tets |\n|---|---|---|---|---|\n");

  struct Case {
    std::string name, file;
    bool draco;
  };
  for (const Case& c : {Case{"binary STL", "mesh.stl", false}, Case{"PLY (binary)", "mesh.ply", false},
                        Case{"OBJ", "mesh.obj", false}, Case{"GLB", "mesh.glb", false},
                        Case{"Draco GLB", "mesh.draco.glb", true}, Case{"Draco .drc", "mesh.drc", false}}) {
    if (!registry.by_extension(c.file)) continue;
    const auto path = dir / c.file;
    mr::io::WriteOptions options;
    options.draco.compress_gltf = c.draco;
    row("write " + c.name, seconds([&] { mr::io::write_surface(registry, soup, path, options); }), path,
        soup.num_triangles());
    mr::TriangleSoup back;
    const double s = seconds([&] { back = mr::io::read_surface(registry, path); });
    row("read " + c.name + " (ours)", s, path, back.num_triangles());
  }
  const mr::TetMesh grid = kuhn_grid(static_cast<std::size_t>(std::cbrt(double(n) / 6)));
  struct VolumeCase {
    std::string name, file, msh_version;
    bool binary;
  };
  for (const VolumeCase& c : {VolumeCase{"MSH 4.1 binary", "tets41b.msh", "4.1", true},
                              VolumeCase{"MSH 4.1 ASCII", "tets41a.msh", "4.1", false},
                              VolumeCase{"MSH 2.2 binary", "tets22b.msh", "2.2", true},
                              VolumeCase{"Medit .mesh", "tets.mesh", "4.1", false},
                              VolumeCase{"VTU (binary)", "tets.vtu", "4.1", true}}) {
    const auto path = dir / c.file;
    mr::io::WriteOptions options;
    options.binary = c.binary;
    options.msh_version = c.msh_version;
    row("write " + c.name + " (tets)", seconds([&] { mr::io::write_volume(registry, grid, path, options); }),
        path, grid.tets.size());
    if (!registry.by_extension(path)->read_volume) continue;
    mr::TetMesh back;
    const double s = seconds([&] { back = mr::io::read_volume(registry, path); });
    row("read " + c.name + " (tets)", s, path, back.tets.size());
  }

  const auto stl = dir / "mesh.stl";
  if (std::filesystem::exists(stl)) {
    mr::TriMesh mesh;
    const double s = seconds([&] { OpenMesh::IO::read_mesh(mesh, stl.string()); });
    row("read binary STL (OpenMesh read_mesh)", s, stl, mesh.n_faces());
  }
  return 0;
}
