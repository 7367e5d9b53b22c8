// Winding number queries per second: the hierarchical evaluation against the
// direct sum, on generated sphere-like meshes of 100k and 1M triangles, on one
// thread and on all threads. Run: winding_number_bench --benchmark_counters_tabular=true
#include <mr/winding_number/winding_number.h>

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>

namespace {

// A bumpy closed sphere: 2 * rings * (segments - 1) triangles.
mr::TriangleSoup bumpy_sphere(int rings, int segments) {
  mr::TriangleSoup soup;
  const auto radius = [](double theta, double phi) {
    return 1.0 + 0.1 * std::sin(5 * theta) * std::cos(7 * phi);
  };
  soup.positions.emplace_back(0, 0, radius(0, 0));
  for (int i = 1; i < segments; ++i) {
    const double theta = std::numbers::pi * i / segments;
    for (int j = 0; j < rings; ++j) {
      const double phi = 2 * std::numbers::pi * j / rings, r = radius(theta, phi);
      soup.positions.emplace_back(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                                  r * std::cos(theta));
    }
  }
  soup.positions.emplace_back(0, 0, -radius(std::numbers::pi, 0));
  const auto ring = [&](int i, int j) { return static_cast<mr::Index>(1 + (i - 1) * rings + (j % rings)); };
  const auto south = static_cast<mr::Index>(soup.positions.size() - 1);
  for (int j = 0; j < rings; ++j) {
    soup.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    soup.triangles.push_back({south, ring(segments - 1, j + 1), ring(segments - 1, j)});
    for (int i = 1; i + 1 < segments; ++i) {
      soup.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      soup.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  }
  return soup;
}

struct Fixture {
  mr::TriangleSoup soup;
  std::unique_ptr<mr::WindingNumberTree> tree;
  std::vector<mr::Vec3d> queries;
};

// Built once per size and kept for the whole run (benchmark code only).
const Fixture& fixture(int faces) {
  static std::map<int, Fixture> cache;
  Fixture& f = cache[faces];
  if (!f.tree) {
    const int rings = static_cast<int>(std::sqrt(faces));
    f.soup = bumpy_sphere(rings, faces / (2 * rings) + 1);
    f.tree = std::make_unique<mr::WindingNumberTree>(f.soup);
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> coordinate(-1.2, 1.2);
    for (int i = 0; i < 200000; ++i)
      f.queries.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
  }
  return f;
}

int thread_count(const benchmark::State& state) {
  return state.range(1) == 0 ? tbb::info::default_concurrency() : static_cast<int>(state.range(1));
}

void BM_Build(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, thread_count(state));
  for (auto _ : state) benchmark::DoNotOptimize(mr::WindingNumberTree(f.soup));
  state.counters["faces"] = static_cast<double>(f.soup.num_triangles());
  state.counters["threads"] = thread_count(state);
}

void BM_Fast(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, thread_count(state));
  for (auto _ : state) benchmark::DoNotOptimize(f.tree->evaluate(f.queries));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(f.queries.size()));
  state.counters["faces"] = static_cast<double>(f.soup.num_triangles());
  state.counters["threads"] = thread_count(state);
}

// The direct sum on a subsample: each query costs a pass over every face.
void BM_Exact(benchmark::State& state) {
  const Fixture& f = fixture(static_cast<int>(state.range(0)));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, thread_count(state));
  const std::size_t subsample = 64;
  std::vector<double> result(subsample);
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, subsample, 1), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
        result[i] = mr::winding_number_exact(f.soup, f.queries[i]);
    });
    benchmark::DoNotOptimize(result.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(subsample));
  state.counters["faces"] = static_cast<double>(f.soup.num_triangles());
  state.counters["threads"] = thread_count(state);
}

// Arguments: {faces, threads (0 = all)}.
void sizes_and_threads(benchmark::internal::Benchmark* b) {
  for (int faces : {100000, 1000000})
    for (int threads : {1, 0}) b->Args({faces, threads});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

}  // namespace

BENCHMARK(BM_Build)->Apply(sizes_and_threads);
BENCHMARK(BM_Fast)->Apply(sizes_and_threads);
BENCHMARK(BM_Exact)->Apply(sizes_and_threads);
BENCHMARK_MAIN();
