// simplify_bench MODEL|gen-torus:FACES [epsilon_rel] [--write-input FILE]: simplify-in-envelope on
// one model, then OpenMesh's plain quadric decimation (Decimater + ModQuadric)
// to the same face count; prints one JSON line with faces, seconds, peak
// memory and the sampled distances output -> input and input -> output (their
// maximum is the Hausdorff distance) of both. One
// model per process so that the peak memory belongs to it (see simplify_bench.sh).

#include "mesh_generators.h"

#include <mr/check/distance.h>
#include <mr/core/openmesh_convert.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/simplify/simplify.h>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

// A bumpy torus with about `faces` triangles (a dense scan-like surface).
mr::TriangleSoup torus(std::size_t faces) {
  const int nu = int(std::sqrt(double(faces)));
  const int nv = int(faces / (2 * std::size_t(nu)));
  return mr::test::torus_grid(nu, nv, [&](int i, int j) {
    const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
    const double r = 0.3 + 0.01 * std::sin(7 * u) * std::cos(5 * v);
    return mr::Vec3d((1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u),
                     r * std::sin(v));
  });
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Plain quadric decimation of the part OpenMesh accepts, to `target` faces.
mr::TriangleSoup openmesh_quadric(const mr::TriangleSoup& input, std::size_t target) {
  mr::TriMesh mesh = mr::to_trimesh(input).mesh;
  using Decimater = OpenMesh::Decimater::DecimaterT<mr::TriMesh>;
  using Quadric = OpenMesh::Decimater::ModQuadricT<mr::TriMesh>::Handle;
  Decimater decimater(mesh);
  Quadric quadric;
  decimater.add(quadric);
  decimater.initialize();
  decimater.decimate_to_faces(0, target);
  mesh.garbage_collection();
  return mr::to_soup(mesh);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string input_copy;  // --write-input FILE: the input as read or generated, for other tools
  if (const auto it = std::find(args.begin(), args.end(), "--write-input");
      it != args.end() && it + 1 != args.end()) {
    input_copy = *(it + 1);
    args.erase(it, it + 2);
  }
  if (args.empty()) {
    std::cerr << "usage: simplify_bench MODEL|gen-torus:FACES [epsilon_rel] [--write-input FILE]\n";
    return 2;
  }
  const std::string model = args[0];
  mr::simplify::SimplifyOptions options;
  if (args.size() > 1) options.epsilon_rel = std::stod(args[1]);
  const auto registry = mr::io::make_default_registry();
  const mr::TriangleSoup input = model.rfind("gen-torus:", 0) == 0 ? torus(std::stoul(model.substr(10)))
                                                                   : mr::io::read_surface(registry, model);
  if (!input_copy.empty()) mr::io::write_surface(registry, input, input_copy);
  const double rss_input = peak_rss_mb();
  auto start = std::chrono::steady_clock::now();
  const auto ours = mr::simplify::simplify_in_envelope(input, options);
  const double ours_seconds = seconds_since(start);
  const double rss_ours = peak_rss_mb();
  const auto ours_distance = mr::check::one_sided_distance(ours.soup, input);
  const auto ours_back = mr::check::one_sided_distance(input, ours.soup);

  start = std::chrono::steady_clock::now();
  const mr::TriangleSoup quadric = openmesh_quadric(input, ours.faces_after);
  const double quadric_seconds = seconds_since(start);
  const auto quadric_distance = mr::check::one_sided_distance(quadric, input);
  const auto quadric_back = mr::check::one_sided_distance(input, quadric);

  std::cout << "{\"model\": \"" << model << "\", \"faces_before\": " << ours.faces_before
            << ", \"faces_after\": " << ours.faces_after << ", \"kept_aside\": " << ours.kept_aside_faces
            << ", \"epsilon_abs\": " << ours.epsilon << ", \"seconds\": " << ours_seconds
            << ", \"seconds_setup\": " << ours.seconds_setup
            << ", \"seconds_collapse\": " << ours.seconds_collapse
            << ", \"seconds_flip\": " << ours.seconds_flip << ", \"peak_rss_mb_input\": " << rss_input
            << ", \"peak_rss_mb\": " << rss_ours << ", \"distance_max\": " << ours_distance.max
            << ", \"distance_back_max\": " << ours_back.max
            << ", \"openmesh_quadric_faces\": " << quadric.triangles.size()
            << ", \"openmesh_quadric_seconds\": " << quadric_seconds
            << ", \"openmesh_quadric_distance_max\": " << quadric_distance.max
            << ", \"openmesh_quadric_distance_back_max\": " << quadric_back.max << "}\n";
  return 0;
}
