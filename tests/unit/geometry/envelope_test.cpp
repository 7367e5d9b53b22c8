#include <mr/core/errors.h>
#include <mr/envelope/envelope.h>
#include <mr/spatial/aabb_tree.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <cmath>
#include <random>
#include <vector>

namespace {

using mr::Vec3d;
using mr::envelope::EnvelopeOptions;
using mr::envelope::make_envelope;
using mr::envelope::SamplingPattern;

constexpr double kEps = 0.01;
const double kRadius = kEps / std::sqrt(3.0);  // covering radius of step d = eps

EnvelopeOptions options_for(SamplingPattern pattern, int stage = 1) {
  EnvelopeOptions options;
  options.epsilon = kEps;
  options.pattern = pattern;
  options.stage = stage;
  return options;
}

// A triangle over the top face (z = 1) of the unit cube, at height h.
std::array<Vec3d, 3> over_top(double h) {
  return {Vec3d(0.2, 0.2, 1 + h), Vec3d(0.8, 0.25, 1 + h), Vec3d(0.4, 0.8, 1 + h)};
}

// Every point of the triangle on a lattice much finer than the sampling step.
std::vector<Vec3d> dense_samples(const Vec3d& a, const Vec3d& b, const Vec3d& c, double spacing) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int n = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
  std::vector<Vec3d> samples;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j)
      samples.push_back(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a));
  }
  return samples;
}

}  // namespace

TEST_CASE("envelope: options are checked", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  EnvelopeOptions options;
  CHECK_THROWS_AS(make_envelope(cube, options), mr::UsageError);  // epsilon 0
  options.epsilon = -1;
  CHECK_THROWS_AS(make_envelope(cube, options), mr::UsageError);
  options.epsilon = NAN;
  CHECK_THROWS_AS(make_envelope(cube, options), mr::UsageError);
  options.epsilon = 0.1;
  options.stage = 0;
  CHECK_THROWS_AS(make_envelope(cube, options), mr::UsageError);
  options.stage = 1;
  options.sampling_step = -0.1;
  CHECK_THROWS_AS(make_envelope(cube, options), mr::UsageError);
  options.sampling_step = 0.0;
  const auto envelope = make_envelope(cube, options);
  CHECK(envelope->epsilon() == 0.1);
  CHECK_FALSE(envelope->is_inside(Vec3d(NAN, 0, 0)));
  CHECK_FALSE(envelope->is_inside(Vec3d(0, 0, 1), Vec3d(INFINITY, 0, 1)));
}

TEST_CASE("envelope: points and segments", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    const auto envelope = make_envelope(cube, options_for(pattern));
    CHECK(envelope->is_inside(Vec3d(0.5, 0.5, 1 + 0.999 * kEps)));
    CHECK_FALSE(envelope->is_inside(Vec3d(0.5, 0.5, 1 + 1.001 * kEps)));
    CHECK(envelope->is_inside(Vec3d(0.5, 0.5, 1 - 0.999 * kEps)));
    CHECK_FALSE(envelope->is_inside(Vec3d(0.5, 0.5, 0.5)));
    // Beyond the corner: distance is to the corner point.
    const double d = 0.99 * kEps / std::sqrt(3.0);
    CHECK(envelope->is_inside(Vec3d(1 + d, 1 + d, 1 + d)));
    CHECK_FALSE(envelope->is_inside(Vec3d(1 + 1.02 * d, 1 + 1.02 * d, 1 + 1.02 * d)));

    const double h = kEps - kEps / 2 - 1e-6;  // segment covering radius is d/2
    CHECK(envelope->is_inside(Vec3d(0.1, 0.2, 1 + h), Vec3d(0.9, 0.7, 1 + h)));
    CHECK(envelope->is_inside(Vec3d(0.3, 0.3, 1 + h), Vec3d(0.3, 0.3, 1 + h)));  // a point
    CHECK_FALSE(envelope->is_inside(Vec3d(0.1, 0.2, 1 + 1.0001 * kEps), Vec3d(0.9, 0.7, 1)));
    // Both ends on the surface, the middle deep inside the cube.
    CHECK_FALSE(envelope->is_inside(Vec3d(0.0, 0.5, 0.5), Vec3d(1.0, 0.5, 0.5)));
    // Along an edge of the cube, then sticking out past a corner by 2 eps.
    CHECK(envelope->is_inside(Vec3d(0, 1, 1), Vec3d(1, 1, 1)));
    CHECK_FALSE(envelope->is_inside(Vec3d(0, 1, 1), Vec3d(1 + 2 * kEps, 1, 1)));
  }
}

TEST_CASE("envelope: triangles nearly parallel to the surface", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    const auto envelope = make_envelope(cube, options_for(pattern));
    const auto inside = [&](const std::array<Vec3d, 3>& t) { return envelope->is_inside(t[0], t[1], t[2]); };
    CHECK(inside(over_top(0.0)));
    CHECK(inside(over_top(kEps - kRadius - 1e-6)));
    CHECK(inside(over_top(-(kEps - kRadius - 1e-6))));
    CHECK_FALSE(inside(over_top(kEps * (1 + 1e-6))));
    CHECK_FALSE(inside(over_top(-kEps * (1 + 1e-6))));
    // Tilted: one corner slightly above epsilon.
    auto tilted = over_top(0.3 * kEps);
    tilted[1].z() = 1 + kEps * (1 + 1e-6);
    CHECK_FALSE(inside(tilted));
    tilted[1].z() = 1 + kEps - kRadius - 1e-6;
    CHECK(inside(tilted));
  }
}

TEST_CASE("envelope: a triangle with all corners inside but its middle outside", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    const auto envelope = make_envelope(cube, options_for(pattern, 3));
    const Vec3d a(0.001, 0.5, 0.5), b(0.999, 0.5, 0.5), c(0.5, 0.999, 0.5);
    REQUIRE(envelope->is_inside(a));
    REQUIRE(envelope->is_inside(b));
    REQUIRE(envelope->is_inside(c));
    CHECK_FALSE(envelope->is_inside(a, b, c));
    // Two opposite faces with a thin gap of 3 eps between them: a triangle
    // bridging the gap has its corners on the faces and its middle 1.5 eps away.
    mr::TriangleSoup two_plates = mr::test::cube_soup(0.0, 1.0);
    mr::TriangleSoup second = mr::test::cube_soup(0.0, 1.0);
    for (Vec3d& p : second.positions) p.z() += 1 + 3 * kEps;
    two_plates.append(second);
    const auto plates = make_envelope(two_plates, options_for(pattern, 4));
    CHECK_FALSE(plates->is_inside(Vec3d(0.2, 0.2, 1), Vec3d(0.8, 0.2, 1), Vec3d(0.5, 0.5, 1 + 3 * kEps)));
    CHECK(plates->is_inside(Vec3d(0.2, 0.2, 1), Vec3d(0.8, 0.2, 1), Vec3d(0.5, 0.5, 1 + 0.2 * kEps)));
  }
}

TEST_CASE("envelope: a large triangle over a finely tessellated plane", "[envelope][slow]") {
  // 200 x 200 cells of the unit square, each two triangles, and a copy with
  // a 0.1 x 0.1 hole: a triangle spanning the square is inside the first,
  // and not the second, though its corners are near the plane in both.
  constexpr int kCells = 200;
  const auto grid = [&](bool with_hole) {
    mr::TriangleSoup soup;
    for (int i = 0; i <= kCells; ++i) {
      for (int j = 0; j <= kCells; ++j)
        soup.positions.emplace_back(double(i) / kCells, double(j) / kCells, 0.0);
    }
    const auto id = [&](int i, int j) { return static_cast<mr::Index>(i * (kCells + 1) + j); };
    for (int i = 0; i < kCells; ++i) {
      for (int j = 0; j < kCells; ++j) {
        if (with_hole && i >= 80 && i < 100 && j >= 40 && j < 60) continue;
        soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
    return soup;
  };
  const Vec3d a(0.01, 0.01, 0.0005), b(0.99, 0.02, -0.0005), c(0.3, 0.98, 0.0);
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    EnvelopeOptions options;
    options.epsilon = 1e-3;
    options.pattern = pattern;
    CHECK(make_envelope(grid(false), options)->is_inside(a, b, c));
    const auto holed = make_envelope(grid(true), options);
    REQUIRE(holed->is_inside(a));
    REQUIRE(holed->is_inside(b));
    REQUIRE(holed->is_inside(c));
    CHECK_FALSE(holed->is_inside(a, b, c));
    CHECK(holed->is_inside(a, c));                                            // the edge misses the hole
    CHECK_FALSE(holed->is_inside(Vec3d(0.45, 0.1, 0), Vec3d(0.45, 0.9, 0)));  // crosses it
  }
}

TEST_CASE("envelope: long thin triangles and triangles over a corner", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    const auto envelope = make_envelope(cube, options_for(pattern));
    const double h = 0.5 * (kEps - kRadius);
    CHECK(envelope->is_inside(Vec3d(0.05, 0.5, 1 + h), Vec3d(0.95, 0.5, 1 + h), Vec3d(0.5, 0.5001, 1 + h)));
    // The same sliver sticking out past the edge x = 1 by 2 eps.
    CHECK_FALSE(envelope->is_inside(Vec3d(0.05, 0.5, 1 + h), Vec3d(1 + 2 * kEps, 0.5, 1 + h),
                                    Vec3d(0.5, 0.5001, 1 + h)));
    // A sliver standing on the surface, reaching 1.01 eps up at its far end only.
    CHECK_FALSE(
        envelope->is_inside(Vec3d(0.05, 0.5, 1), Vec3d(0.95, 0.5, 1 + 1.01 * kEps), Vec3d(0.5, 0.5001, 1)));
    // Hovering over the corner (1,1,1): flat at height 0.2 eps, reaching 0.3 eps
    // past the corner in x and y. Outside the cube the distance is convex, so
    // the corners are the farthest points: at most 0.36 eps < eps - r.
    const double z = 1 + 0.2 * kEps;
    CHECK(envelope->is_inside(Vec3d(0.9, 0.9, z), Vec3d(1 + 0.3 * kEps, 0.9, z),
                              Vec3d(0.9, 1 + 0.3 * kEps, z)));
    // The same shape reaching 1.1 eps past the corner.
    CHECK_FALSE(envelope->is_inside(Vec3d(0.9, 0.9, z), Vec3d(1 + 1.1 * kEps, 1 + 0.5 * kEps, z),
                                    Vec3d(0.9, 1 + 1.1 * kEps, z)));
    // Perpendicular to the corner's diagonal at distance 1.05 eps: every point beyond eps.
    const Vec3d n = Vec3d(1, 1, 1).normalized();
    const Vec3d u = Vec3d(1, -1, 0).normalized();
    const Vec3d w = n.cross(u);
    const Vec3d center = Vec3d(1, 1, 1) + 1.05 * kEps * n;
    CHECK_FALSE(
        envelope->is_inside(center + 0.1 * kEps * u, center + 0.1 * kEps * w, center - 0.1 * kEps * u));
  }
}

TEST_CASE("envelope: degenerate triangles", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    const auto envelope = make_envelope(cube, options_for(pattern));
    const Vec3d p(0.5, 0.5, 1 + 0.5 * kEps);
    CHECK(envelope->is_inside(p, p, p));
    const Vec3d q(0.5, 0.5, 1 + 1.5 * kEps);
    CHECK_FALSE(envelope->is_inside(q, q, q));
    // Collinear corners; the middle corner listed last.
    CHECK(envelope->is_inside(Vec3d(0.1, 0.5, 1), Vec3d(0.9, 0.5, 1), Vec3d(0.5, 0.5, 1)));
    CHECK_FALSE(envelope->is_inside(Vec3d(0, 0.5, 0.5), Vec3d(1, 0.5, 0.5), Vec3d(0.5, 0.5, 0.5)));
    CHECK_FALSE(envelope->is_inside(Vec3d(0, 0.5, 0.5), Vec3d(1, 0.5, 0.5), Vec3d(0, 0.5, 0.5)));
  }
  const auto empty = make_envelope(mr::TriangleSoup{}, options_for(SamplingPattern::Adaptive));
  CHECK_FALSE(empty->is_inside(Vec3d(0, 0, 0)));
  CHECK_FALSE(empty->is_inside(Vec3d(0, 0, 0), Vec3d(0, 0, 0), Vec3d(0, 0, 0)));
}

TEST_CASE("envelope: staged refinement widens the conservative envelope", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  // Longest edge exactly 10 steps: the lattice has n = 10 k.
  const double h = kEps - 0.75 * kRadius;
  const Vec3d a(0.2, 0.2, 1 + h), b(0.2 + 10 * kEps, 0.2, 1 + h), c(0.2, 0.2 + 5 * kEps, 1 + h);
  CHECK_FALSE(make_envelope(cube, options_for(SamplingPattern::Lattice, 1))->is_inside(a, b, c));
  CHECK(make_envelope(cube, options_for(SamplingPattern::Lattice, 2))->is_inside(a, b, c));
  CHECK(make_envelope(cube, options_for(SamplingPattern::Adaptive, 2))->is_inside(a, b, c));
}

// Random soup: small triangles near a bumpy sphere. Random query triangles
// around it: whenever the envelope says inside, a lattice 20 times finer
// than the sampling step must find every point within epsilon.
TEST_CASE("envelope: never inside when some point is farther than epsilon", "[envelope][slow]") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto random_vector = [&] { return Vec3d(unit(rng), unit(rng), unit(rng)); };
  mr::TriangleSoup soup;
  for (int t = 0; t < 400; ++t) {
    const Vec3d center = random_vector().normalized() * (1 + 0.05 * unit(rng));
    const auto first = static_cast<mr::Index>(soup.positions.size());
    for (int k = 0; k < 3; ++k) soup.positions.push_back(center + 0.15 * random_vector());
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const double eps = 0.02;
  const mr::spatial::AabbTree exact(soup);
  for (const auto pattern : {SamplingPattern::Adaptive, SamplingPattern::Lattice}) {
    for (const int stage : {1, 2}) {
      EnvelopeOptions options;
      options.epsilon = eps;
      options.pattern = pattern;
      options.stage = stage;
      const auto envelope = make_envelope(soup, options);
      int inside_count = 0;
      for (int q = 0; q < 1500; ++q) {
        const auto& tri = soup.triangles[rng() % soup.triangles.size()];
        const Vec3d base = soup.positions[tri[q % 3]] + 0.7 * eps * random_vector();
        const double size = eps * (q % 3 == 0 ? 0.3 : q % 3 == 1 ? 3.0 : 20.0);
        const Vec3d a = base;
        const Vec3d b = base + size * random_vector();
        const Vec3d c = q % 5 == 0 ? Vec3d(base + 0.01 * (b - base) + 1e-4 * eps * random_vector())
                                   : Vec3d(base + size * random_vector());
        if (!envelope->is_inside(a, b, c)) continue;
        ++inside_count;
        for (const Vec3d& p : dense_samples(a, b, c, eps / (stage * 20.0))) {
          REQUIRE(exact.squared_distance(p) <= eps * eps);
        }
      }
      INFO("pattern " << int(pattern) << " stage " << stage);
      CHECK(inside_count > 150);  // the check above must not be vacuous
    }
  }
}

TEST_CASE("envelope: batch answers match one by one, deterministically", "[envelope]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  const auto envelope = make_envelope(cube, options_for(SamplingPattern::Adaptive));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.05, 1.05);
  std::vector<mr::envelope::TriangleCorners> triangles;
  for (int t = 0; t < 3000; ++t) {
    const Vec3d a(u(rng), u(rng), 1 + 0.02 * (u(rng) - 0.5));
    triangles.push_back({a, a + Vec3d(0.03 * u(rng), 0.03 * u(rng), 0.005 * u(rng)),
                         a + Vec3d(0.03 * u(rng), 0.03 * u(rng), 0.005 * u(rng))});
  }
  const std::vector<std::uint8_t> batch = envelope->are_inside(triangles);
  REQUIRE(batch.size() == triangles.size());
  int inside = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    REQUIRE((batch[t] == 1) == envelope->is_inside(triangles[t][0], triangles[t][1], triangles[t][2]));
    inside += batch[t];
  }
  CHECK(inside > 100);
  CHECK(inside < 2900);
  CHECK(envelope->are_inside(triangles) == batch);
  CHECK(envelope->are_inside(cube) == std::vector<std::uint8_t>(12, 1));
}
