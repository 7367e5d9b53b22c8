// orient3d throughput, one thread: mr::orient3d (an out-of-line wrapper over
// CGAL's Epick predicate) against the Epick functor inlined here, a plain
// double determinant (not exact; the speed ceiling), the hybrid version with
// one rational point (interval filter, then GMP), and pure GMP rationals.
//   random:          uniform points in a cube; the filter decides everything.
//   near_degenerate: the fourth point is the double nearest to a point of the
//                    plane of the other three; most calls fail the filter.
//   coplanar:        exactly coplanar lattice points (sign 0, exact path).
// Run: /tmp/build-kernel/bench/kernel_bench --benchmark_min_time=0.5

#include <mr/kernel/hybrid_point.h>
#include <mr/kernel/predicates.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <vector>

namespace {

using Quad = std::array<mr::Vec3d, 4>;
constexpr std::size_t kInputs = 4096;

std::vector<Quad> random_quads() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Quad> quads(kInputs);
  for (Quad& q : quads) {
    for (mr::Vec3d& p : q) p = mr::Vec3d(unit(rng), unit(rng), unit(rng));
  }
  return quads;
}

std::vector<Quad> near_degenerate_quads() {
  std::vector<Quad> quads = random_quads();
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (Quad& q : quads) q[3] = q[0] + unit(rng) * (q[1] - q[0]) + unit(rng) * (q[2] - q[0]);
  return quads;
}

std::vector<Quad> coplanar_quads() {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> small(-1000, 1000);
  std::vector<Quad> quads(kInputs);
  for (Quad& q : quads) {
    for (mr::Vec3d& p : q) {
      const double y = small(rng), z = small(rng);
      p = mr::Vec3d(-2 * y - 3 * z, y, z) * 0x1p-20;
    }
  }
  return quads;
}

const std::vector<Quad>& inputs(int kind) {
  static const std::vector<Quad> sets[3] = {random_quads(), near_degenerate_quads(), coplanar_quads()};
  return sets[kind];
}

template <class Predicate>
void run(benchmark::State& state, Predicate predicate) {
  const std::vector<Quad>& quads = inputs(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Quad& q = quads[i++ % quads.size()];
    benchmark::DoNotOptimize(predicate(q));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_orient3d_mr(benchmark::State& state) {
  run(state, [](const Quad& q) { return mr::orient3d(q[0], q[1], q[2], q[3]); });
}

void BM_orient3d_cgal_epick(benchmark::State& state) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const K::Orientation_3 orientation;
  run(state, [&](const Quad& q) {
    auto p = [](const mr::Vec3d& v) { return K::Point_3(v.x(), v.y(), v.z()); };
    return static_cast<int>(orientation(p(q[0]), p(q[1]), p(q[2]), p(q[3])));
  });
}

void BM_orient3d_naive_double(benchmark::State& state) {
  run(state, [](const Quad& q) {
    const double det = (q[1] - q[0]).cross(q[2] - q[0]).dot(q[3] - q[0]);
    return (det > 0) - (det < 0);
  });
}

void BM_orient3d_hybrid_one_rational(benchmark::State& state) {
  const std::vector<Quad>& quads = inputs(static_cast<int>(state.range(0)));
  std::vector<mr::HybridPoint> rational;
  for (const Quad& q : quads) {
    mr::ExactPoint3 moved(q[3]);
    moved.x += mpq_class(1, 3) * mpq_class(0x1p-60);  // not a double any more
    rational.push_back(mr::HybridPoint::from_exact(moved));
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % quads.size();
    const Quad& q = quads[k];
    benchmark::DoNotOptimize(mr::orient3d(mr::HybridPoint(q[0]), q[1], q[2], rational[k]));
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_orient3d_gmp_rational(benchmark::State& state) {
  const std::vector<Quad>& quads = inputs(static_cast<int>(state.range(0)));
  std::vector<std::array<mr::ExactPoint3, 4>> exact;
  for (const Quad& q : quads) {
    exact.push_back(
        {mr::ExactPoint3(q[0]), mr::ExactPoint3(q[1]), mr::ExactPoint3(q[2]), mr::ExactPoint3(q[3])});
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& e = exact[i++ % exact.size()];
    benchmark::DoNotOptimize(mr::orient3d(e[0], e[1], e[2], e[3]));
  }
  state.SetItemsProcessed(state.iterations());
}

// Argument: 0 = random, 1 = near_degenerate, 2 = coplanar.
BENCHMARK(BM_orient3d_mr)->DenseRange(0, 2);
BENCHMARK(BM_orient3d_cgal_epick)->DenseRange(0, 2);
BENCHMARK(BM_orient3d_naive_double)->DenseRange(0, 2);
BENCHMARK(BM_orient3d_hybrid_one_rational)->DenseRange(0, 2);
BENCHMARK(BM_orient3d_gmp_rational)->DenseRange(0, 2);

}  // namespace

BENCHMARK_MAIN();
