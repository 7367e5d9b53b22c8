// AABB tree against CGAL's AABB_tree (build, closest point, "any within r"),
// and envelope triangle checks per second. CGAL stays in this file only.
//   spatial_bench --benchmark_filter=Build

#include "mesh_generators.h"

#include <mr/envelope/envelope.h>
#include <mr/spatial/aabb_tree.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <vector>

namespace {

using mr::Vec3d;
using K = CGAL::Epick;
using CgalTriangles = std::vector<K::Triangle_3>;
using CgalPrimitive = CGAL::AABB_triangle_primitive<K, CgalTriangles::const_iterator>;
using CgalTree = CGAL::AABB_tree<CGAL::AABB_traits<K, CgalPrimitive>>;

constexpr int kQueries = 100000;

// A torus with bumps, nu * nv * 2 triangles, bounding box diagonal about 4.
mr::TriangleSoup bumpy_torus(int nu, int nv) {
  const double pi = std::acos(-1.0);
  return mr::test::torus_grid(nu, nv, [&](int i, int j) {
    const double u = 2 * pi * i / nu, v = 2 * pi * j / nv;
    const double r = 0.4 * (1 + 0.05 * std::sin(7 * u) * std::sin(5 * v));
    return mr::Vec3d((1 + r * std::cos(v)) * std::cos(u), (1 + r * std::cos(v)) * std::sin(u),
                     r * std::sin(v));
  });
}

const mr::TriangleSoup& torus(std::int64_t faces) {
  static std::map<std::int64_t, mr::TriangleSoup> cache;
  auto it = cache.find(faces);
  if (it == cache.end()) {
    const int nu = faces >= 1000000 ? 1000 : 250;
    it = cache.emplace(faces, bumpy_torus(nu, static_cast<int>(faces / (2 * nu)))).first;
  }
  return it->second;
}

CgalTriangles to_cgal(const mr::TriangleSoup& soup) {
  CgalTriangles triangles;
  triangles.reserve(soup.triangles.size());
  const auto point = [&](mr::Index v) {
    return K::Point_3(soup.positions[v].x(), soup.positions[v].y(), soup.positions[v].z());
  };
  for (const auto& t : soup.triangles) triangles.emplace_back(point(t[0]), point(t[1]), point(t[2]));
  return triangles;
}

// Half the queries near the surface (within 1% of the diagonal), half
// anywhere in the bounding box grown by 10%.
std::vector<Vec3d> queries(const mr::TriangleSoup& soup) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec3d> points;
  for (int q = 0; q < kQueries; ++q) {
    if (q % 2 == 0) {
      const Vec3d& p = soup.positions[rng() % soup.positions.size()];
      points.push_back(p + 0.04 * Vec3d(unit(rng), unit(rng), unit(rng)));
    } else {
      points.push_back(Vec3d(1.6 * unit(rng), 1.6 * unit(rng), 0.5 * unit(rng)));
    }
  }
  return points;
}

// state.range(1): 1 one thread, 0 all threads.
void BM_AabbBuild(benchmark::State& state) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  std::optional<tbb::global_control> one_thread;
  if (state.range(1) == 1) one_thread.emplace(tbb::global_control::max_allowed_parallelism, 1);
  for (auto _ : state) {
    const mr::spatial::AabbTree tree(soup);
    benchmark::DoNotOptimize(tree.num_triangles());
  }
}

// Build of the AABB tree plus the kd-tree CGAL uses to start distance queries.
void BM_CgalBuild(benchmark::State& state) {
  const CgalTriangles triangles = to_cgal(torus(state.range(0)));
  for (auto _ : state) {
    CgalTree tree(triangles.begin(), triangles.end());
    tree.build();
    tree.accelerate_distance_queries();
    benchmark::DoNotOptimize(tree.size());
  }
}

void BM_AabbClosest(benchmark::State& state) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  const mr::spatial::AabbTree tree(soup);
  const std::vector<Vec3d> points = queries(soup);
  for (auto _ : state) {
    for (const Vec3d& p : points) benchmark::DoNotOptimize(tree.closest(p).squared_distance);
  }
  state.SetItemsProcessed(state.iterations() * kQueries);
}

void BM_CgalClosest(benchmark::State& state) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  const CgalTriangles triangles = to_cgal(soup);
  CgalTree tree(triangles.begin(), triangles.end());
  tree.build();
  tree.accelerate_distance_queries();
  const std::vector<Vec3d> points = queries(soup);
  for (auto _ : state) {
    for (const Vec3d& p : points) {
      benchmark::DoNotOptimize(tree.closest_point_and_primitive(K::Point_3(p.x(), p.y(), p.z())));
    }
  }
  state.SetItemsProcessed(state.iterations() * kQueries);
}

constexpr double kWithin = 0.004;  // 1e-3 of the diagonal, the paper's epsilon

void BM_AabbAnyWithin(benchmark::State& state) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  const mr::spatial::AabbTree tree(soup);
  const std::vector<Vec3d> points = queries(soup);
  for (auto _ : state) {
    for (const Vec3d& p : points) benchmark::DoNotOptimize(tree.any_within(p, kWithin));
  }
  state.SetItemsProcessed(state.iterations() * kQueries);
}

void BM_CgalAnyWithin(benchmark::State& state) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  const CgalTriangles triangles = to_cgal(soup);
  CgalTree tree(triangles.begin(), triangles.end());
  tree.build();
  const std::vector<Vec3d> points = queries(soup);
  for (auto _ : state) {
    for (const Vec3d& p : points) {
      const K::Sphere_3 ball(K::Point_3(p.x(), p.y(), p.z()), kWithin * kWithin);
      benchmark::DoNotOptimize(tree.do_intersect(ball));
    }
  }
  state.SetItemsProcessed(state.iterations() * kQueries);
}

// Envelope checks: the input's own triangles, corners moved by up to 0.3 eps
// per coordinate. state.range(1): 0 one thread (loop), 1 all threads (batch).
void envelope_checks(benchmark::State& state, mr::envelope::SamplingPattern pattern) {
  const mr::TriangleSoup& soup = torus(state.range(0));
  mr::envelope::EnvelopeOptions options;
  options.epsilon = kWithin;
  options.pattern = pattern;
  const auto envelope = mr::envelope::make_envelope(soup, options);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> noise(-0.3 * kWithin, 0.3 * kWithin);
  std::vector<mr::envelope::TriangleCorners> triangles;
  for (const auto& t : soup.triangles) {
    mr::envelope::TriangleCorners corners;
    for (int k = 0; k < 3; ++k) corners[k] = soup.positions[t[k]] + Vec3d(noise(rng), noise(rng), noise(rng));
    triangles.push_back(corners);
  }
  std::size_t inside = 0;
  for (auto _ : state) {
    inside = 0;
    if (state.range(1) == 0) {
      for (const auto& t : triangles) inside += envelope->is_inside(t[0], t[1], t[2]) ? 1 : 0;
    } else {
      for (const std::uint8_t answer : envelope->are_inside(triangles)) inside += answer;
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(triangles.size()));
  state.counters["inside_fraction"] = static_cast<double>(inside) / static_cast<double>(triangles.size());
}

void BM_EnvelopeAdaptive(benchmark::State& state) {
  envelope_checks(state, mr::envelope::SamplingPattern::Adaptive);
}
void BM_EnvelopeLattice(benchmark::State& state) {
  envelope_checks(state, mr::envelope::SamplingPattern::Lattice);
}

}  // namespace

BENCHMARK(BM_AabbBuild)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Args({1000000, 0})
    ->Args({1000000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_CgalBuild)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AabbClosest)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CgalClosest)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AabbAnyWithin)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CgalAnyWithin)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EnvelopeAdaptive)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_EnvelopeLattice)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_MAIN();
