#include <mr/core/errors.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/spatial/triangle_distance.h>

#include <catch2/catch.hpp>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

namespace {

using mr::Vec3d;
using mr::spatial::AabbTree;
using mr::spatial::closest_on_triangle;

Vec3d random_point(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return {u(rng), u(rng), u(rng)};
}

// Small random triangles scattered in [0,1]^3, some degenerate.
mr::TriangleSoup random_soup(std::mt19937_64& rng, int count) {
  mr::TriangleSoup soup;
  std::uniform_real_distribution<double> size(0.001, 0.1);
  for (int t = 0; t < count; ++t) {
    const Vec3d base = random_point(rng, 0.0, 1.0);
    const double s = size(rng);
    const auto first = static_cast<mr::Index>(soup.positions.size());
    soup.positions.push_back(base);
    if (t % 17 == 0) {  // a point
      soup.positions.push_back(base);
      soup.positions.push_back(base);
    } else if (t % 13 == 0) {  // a segment, with the middle corner between the ends
      const Vec3d dir = random_point(rng, -s, s);
      soup.positions.push_back(base + dir);
      soup.positions.push_back(base + 0.3 * dir);
    } else {
      soup.positions.push_back(base + random_point(rng, -s, s));
      soup.positions.push_back(base + random_point(rng, -s, s));
    }
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  return soup;
}

struct BruteHit {
  double squared_distance = INFINITY;
  std::vector<std::uint32_t> nearest;  // every triangle at that distance
};

BruteHit brute_force(const mr::TriangleSoup& soup, const Vec3d& p) {
  BruteHit best;
  for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
    const auto& tri = soup.triangles[t];
    const double d =
        closest_on_triangle(p, soup.positions[tri[0]], soup.positions[tri[1]], soup.positions[tri[2]])
            .squared_distance;
    if (d < best.squared_distance)
      best = {d, {t}};
    else if (d == best.squared_distance)
      best.nearest.push_back(t);
  }
  return best;
}

bool close_relative(double a, double b, double tolerance = 1e-12) {
  return std::abs(a - b) <= tolerance * std::max({std::abs(a), std::abs(b), 1e-300});
}

}  // namespace

TEST_CASE("closest point on a triangle: regions and degenerate triangles", "[aabb]") {
  const Vec3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  CHECK(closest_on_triangle({0.5, 0.5, 3}, a, b, c).squared_distance == Approx(9.0));
  CHECK(closest_on_triangle({-1, -1, 0}, a, b, c).point.isApprox(a));
  CHECK(closest_on_triangle({3, -1, 0}, a, b, c).point.isApprox(b));
  CHECK(closest_on_triangle({1, -2, 1}, a, b, c).squared_distance == Approx(5.0));
  CHECK(closest_on_triangle({2, 2, 0}, a, b, c).squared_distance == Approx(2.0));
  // A segment (collinear corners, middle one listed last) and a point.
  const Vec3d s0(0, 0, 0), s1(4, 0, 0), s2(1, 0, 0);
  CHECK(closest_on_triangle({2, 3, 0}, s0, s1, s2).squared_distance == Approx(9.0));
  CHECK(closest_on_triangle({6, 0, 0}, s0, s1, s2).squared_distance == Approx(4.0));
  CHECK(closest_on_triangle({1, 1, 1}, a, a, a).squared_distance == Approx(3.0));
}

TEST_CASE("squared distance to a triangle agrees with the closest point, in every region", "[aabb]") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> flatten(0.0, 1.0);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3d a = random_point(rng, -1, 1), b = random_point(rng, -1, 1);
    // Every fourth triangle thin or degenerate: c near or on the line ab.
    Vec3d c = random_point(rng, -1, 1);
    if (trial % 4 == 0) c = a + flatten(rng) * (b - a) + std::pow(10.0, -3.0 * (trial % 7)) * (c - a);
    if (trial % 50 == 0) c = b;
    for (int i = 0; i < 20; ++i) {
      const Vec3d p = random_point(rng, -2, 2);
      const double reference = closest_on_triangle(p, a, b, c).squared_distance;
      const double fast = mr::spatial::squared_distance_to_triangle(p, a, b, c);
      CHECK(fast == Approx(reference).epsilon(1e-9).margin(1e-12));
      ++compared;
    }
  }
  CHECK(compared == 40000);
}

TEST_CASE("AABB tree agrees with brute force on random soups", "[aabb]") {
  std::mt19937_64 rng(42);
  for (const int count : {1, 2, 5, 100, 3000}) {
    const mr::TriangleSoup soup = random_soup(rng, count);
    const bool cut = count % 2 == 0;  // the larger triangles cut into pieces in 2, 100 and 3000
    const AabbTree tree(soup, {.cut_large_triangles = cut});
    REQUIRE(tree.num_triangles() == soup.triangles.size());
    for (int q = 0; q < 400; ++q) {
      const Vec3d p = random_point(rng, q % 4 == 0 ? -3.0 : -0.1, q % 4 == 0 ? 4.0 : 1.1);
      const BruteHit expected = brute_force(soup, p);
      const mr::spatial::ClosestHit hit = tree.closest(p);
      REQUIRE(hit.found());
      REQUIRE(close_relative(hit.squared_distance, expected.squared_distance));
      CHECK(std::find(expected.nearest.begin(), expected.nearest.end(), hit.triangle) !=
            expected.nearest.end());
      // The reported point is on the reported triangle and at the reported distance.
      const auto& tri = soup.triangles[hit.triangle];
      CHECK(closest_on_triangle(hit.point, soup.positions[tri[0]], soup.positions[tri[1]],
                                soup.positions[tri[2]])
                .squared_distance <= 1e-20);
      CHECK(close_relative((hit.point - p).squaredNorm(), hit.squared_distance, 1e-9));

      const double r = std::sqrt(expected.squared_distance);
      CHECK(tree.any_within(p, r * (1 + 1e-9)));
      CHECK_FALSE(tree.any_within(p, r * (1 - 1e-9)));
      CHECK_FALSE(tree.closest_within(p, r * (1 - 1e-9)).found());
      CHECK(close_relative(tree.closest_within(p, r * 1.5).squared_distance, expected.squared_distance));
      const double bounded = tree.squared_distance_bounded(p, 0.25 * r * r, 4 * r * r);
      CHECK(close_relative(bounded, expected.squared_distance));
      const double early = tree.squared_distance_bounded(p, 4 * r * r, 4 * r * r);
      CHECK(early >= expected.squared_distance * (1 - 1e-12));
      CHECK(early <= 4 * r * r);
    }
  }
}

TEST_CASE("AABB tree: one triangle near all points agrees with brute force", "[aabb]") {
  std::mt19937_64 rng(7);
  const mr::TriangleSoup soup = random_soup(rng, 300);
  const AabbTree tree(soup, {.cut_large_triangles = true});
  int near_count = 0;
  for (int q = 0; q < 600; ++q) {
    // Near a random triangle, so that both answers occur.
    const auto& host = soup.triangles[rng() % soup.triangles.size()];
    const Vec3d on_host = (soup.positions[host[0]] + soup.positions[host[1]] + soup.positions[host[2]]) / 3.0;
    const Vec3d a = on_host + 0.01 * random_point(rng, -1.0, 1.0);
    const Vec3d b = a + 0.03 * random_point(rng, -1.0, 1.0);
    const Vec3d c = a + 0.03 * random_point(rng, -1.0, 1.0);
    const double r_sq = 0.02 * 0.02;
    const std::array<Vec3d, 3> points{a, b, c};
    bool expected = false;
    for (const auto& t : soup.triangles) {
      const auto near = [&](const Vec3d& p) {
        return closest_on_triangle(p, soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]])
                   .squared_distance <= r_sq;
      };
      expected = expected || (near(a) && near(b) && near(c));
    }
    near_count += expected;
    CHECK(tree.one_triangle_near_all(points, r_sq) == expected);
    CHECK(tree.one_triangle_near_all(std::span(points.data(), 1), r_sq) == tree.any_within(a, 0.02));
  }
  CHECK(near_count > 20);  // both answers occur
  CHECK(near_count < 580);
}

TEST_CASE("AABB tree: queries on the surface and far away", "[aabb]") {
  const mr::TriangleSoup cube = mr::test::cube_soup();
  const AabbTree tree(cube);
  CHECK(tree.closest({0.5, 0.5, 1.0}).squared_distance == 0.0);
  CHECK(tree.closest({0.3, 0.0, 0.7}).squared_distance <= 1e-30);
  CHECK(tree.any_within({1.0, 1.0, 1.0}, 0.0));
  CHECK(tree.closest({0.5, 0.5, 0.5}).squared_distance == Approx(0.25));
  const mr::spatial::ClosestHit far = tree.closest({1e6, 0.5, 0.5});
  CHECK(far.squared_distance == Approx((1e6 - 1) * (1e6 - 1)));
  CHECK(far.point.isApprox(Vec3d(1, 0.5, 0.5)));
  CHECK(tree.any_within({1e6, 0.5, 0.5}, 1e6));
  CHECK_FALSE(tree.any_within({1e6, 0.5, 0.5}, 1e5));
  CHECK_FALSE(tree.any_within({0.5, 0.5, 0.5}, -1.0));
  const mr::spatial::AabbBox box = tree.bounds();
  CHECK(box.lo.isApprox(Vec3d(0, 0, 0)));
  CHECK(box.hi.isApprox(Vec3d(1, 1, 1)));
}

TEST_CASE("AABB tree: empty soup, degenerate-only soup and bad input", "[aabb]") {
  const AabbTree empty{mr::TriangleSoup{}};
  CHECK(empty.empty());
  CHECK_FALSE(empty.closest({0, 0, 0}).found());
  CHECK_FALSE(empty.any_within({0, 0, 0}, 1e300));

  mr::TriangleSoup points;
  points.positions = {{1, 1, 1}, {3, 1, 1}};
  points.triangles = {{0, 0, 0}, {1, 1, 1}, {0, 1, 1}};
  const AabbTree tree(points);
  CHECK(tree.closest({1, 1, 0}).squared_distance == Approx(1.0));
  CHECK(tree.closest({2, 5, 1}).squared_distance == Approx(16.0));
  CHECK(tree.closest({2, 5, 1}).triangle == 2u);

  mr::TriangleSoup bad = mr::test::cube_soup();
  bad.triangles[3][1] = 100;
  CHECK_THROWS_AS(AabbTree(bad), mr::UsageError);
  mr::TriangleSoup nan_soup = mr::test::cube_soup();
  nan_soup.positions[2].x() = NAN;
  CHECK_THROWS_AS(AabbTree(nan_soup), mr::UsageError);
}

TEST_CASE("AABB tree: concurrent queries give the same answers", "[aabb]") {
  std::mt19937_64 rng(7);
  const mr::TriangleSoup soup = random_soup(rng, 20000);
  const AabbTree tree(soup);
  std::vector<Vec3d> queries;
  for (int q = 0; q < 4000; ++q) queries.push_back(random_point(rng, -0.2, 1.2));
  std::vector<mr::spatial::ClosestHit> serial;
  for (const Vec3d& p : queries) serial.push_back(tree.closest(p));

  constexpr int kThreads = 6;
  std::vector<std::vector<mr::spatial::ClosestHit>> results(
      kThreads, std::vector<mr::spatial::ClosestHit>(queries.size()));
  std::vector<std::vector<char>> within(kThreads, std::vector<char>(queries.size()));
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (std::size_t i = 0; i < queries.size(); ++i) {
        const std::size_t q = (i + 977 * t) % queries.size();  // a different order each
        results[t][q] = tree.closest(queries[q]);
        within[t][q] = tree.any_within(queries[q], 0.01) ? 1 : 0;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    for (std::size_t i = 0; i < queries.size(); ++i) {
      REQUIRE(results[t][i].triangle == serial[i].triangle);
      REQUIRE(results[t][i].squared_distance == serial[i].squared_distance);
      REQUIRE(results[t][i].point == serial[i].point);
      REQUIRE((within[t][i] == 1) == (serial[i].squared_distance <= 0.01 * 0.01));
    }
  }
}

TEST_CASE("AABB tree: build is deterministic", "[aabb]") {
  std::mt19937_64 rng(3);
  const mr::TriangleSoup soup = random_soup(rng, 50000);
  const AabbTree first(soup);
  const AabbTree second(soup);
  for (int q = 0; q < 500; ++q) {
    const Vec3d p = random_point(rng, 0.0, 1.0);
    const auto a = first.closest(p);
    const auto b = second.closest(p);
    REQUIRE(a.triangle == b.triangle);
    REQUIRE(a.squared_distance == b.squared_distance);
  }
}

// Triangles as wide as the soup and long thin slivers across it: the build
// cuts them into pieces, and every query must still answer for the whole
// triangle, each triangle once.
TEST_CASE("AABB tree: triangles spanning the soup agree with brute force", "[aabb]") {
  std::mt19937_64 rng(5);
  mr::TriangleSoup soup;
  for (int t = 0; t < 60; ++t) {
    const Vec3d a = random_point(rng, 0.0, 1.0);
    const Vec3d b = random_point(rng, 0.0, 1.0);
    const Vec3d c =
        t % 2 == 0 ? random_point(rng, 0.0, 1.0) : a + 0.3 * (b - a) + random_point(rng, -1e-3, 1e-3);
    const auto first = static_cast<mr::Index>(soup.positions.size());
    soup.positions.insert(soup.positions.end(), {a, b, c});
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const AabbTree tree(soup, {.cut_large_triangles = true});
  REQUIRE(tree.num_triangles() == soup.triangles.size());
  const auto distance_sq = [&](std::uint32_t t, const Vec3d& p) {
    const auto& f = soup.triangles[t];
    return closest_on_triangle(p, soup.positions[f[0]], soup.positions[f[1]], soup.positions[f[2]])
        .squared_distance;
  };
  int boxes_with_triangles = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3d p = random_point(rng, -0.2, 1.2);
    const BruteHit expected = brute_force(soup, p);
    REQUIRE(close_relative(tree.closest(p).squared_distance, expected.squared_distance));
    const double r = std::sqrt(expected.squared_distance);
    CHECK(
        close_relative(tree.squared_distance_bounded(p, 0.25 * r * r, 4 * r * r), expected.squared_distance));

    const double radius = 0.05;
    std::vector<std::uint32_t> near;
    for (std::uint32_t t = 0; t < soup.triangles.size(); ++t)
      if (distance_sq(t, p) <= radius * radius) near.push_back(t);
    CHECK(tree.triangles_within(p, radius) == near);

    // Every triangle with a point in the box is listed, once, and no
    // triangle whose own box misses it.
    const Vec3d lo = p - Vec3d::Constant(radius), hi = p + Vec3d::Constant(radius);
    std::vector<std::uint32_t> in_box;
    tree.triangles_in_box(lo, hi, in_box);
    std::vector<std::uint32_t> sorted = in_box;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());
    for (std::uint32_t t = 0; t < soup.triangles.size(); ++t) {
      const auto& f = soup.triangles[t];
      const Vec3d &a = soup.positions[f[0]], &b = soup.positions[f[1]], &c = soup.positions[f[2]];
      const bool listed = std::binary_search(sorted.begin(), sorted.end(), t);
      const bool own_box_meets = (a.cwiseMin(b).cwiseMin(c).array() <= hi.array()).all() &&
                                 (lo.array() <= a.cwiseMax(b).cwiseMax(c).array()).all();
      CHECK((own_box_meets || !listed));
      bool has_point_inside = false;
      for (int i = 0; i <= 40 && !has_point_inside; ++i)
        for (int j = 0; i + j <= 40 && !has_point_inside; ++j) {
          const Vec3d x = a + (i / 40.0) * (b - a) + (j / 40.0) * (c - a);
          has_point_inside = (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
        }
      if (has_point_inside) CHECK(listed);
    }
    boxes_with_triangles += !in_box.empty();

    const std::array<Vec3d, 2> pair{p, p + random_point(rng, -0.1, 0.1)};
    bool expected_near_all = false;
    for (std::uint32_t t = 0; t < soup.triangles.size(); ++t)
      expected_near_all = expected_near_all || (distance_sq(t, pair[0]) <= radius * radius &&
                                                distance_sq(t, pair[1]) <= radius * radius);
    CHECK(tree.one_triangle_near_all(pair, radius * radius) == expected_near_all);
  }
  CHECK(boxes_with_triangles > 50);  // both answers occur
  CHECK(boxes_with_triangles < 250);
}

TEST_CASE("AABB tree: the triangles near a box answer as the tree does inside it", "[aabb]") {
  std::mt19937_64 rng(11);
  for (const bool cut : {false, true}) {
    const mr::TriangleSoup soup = random_soup(rng, 400);
    const AabbTree tree(soup, {.cut_large_triangles = cut});
    const double radius = 0.03;
    int listed = 0, overflowed = 0;
    for (int q = 0; q < 200; ++q) {
      const Vec3d a = random_point(rng, -0.05, 1.05);
      const Vec3d b = a + random_point(rng, -0.05, 0.05);
      const Vec3d lo = a.cwiseMin(b) - Vec3d::Constant(radius), hi = a.cwiseMax(b) + Vec3d::Constant(radius);
      const mr::spatial::LocalTriangles local(tree, lo, hi, q % 2 == 0 ? 24 : 3);
      if (local.overflowed()) {
        ++overflowed;
        CHECK(local.size() == 0);
        continue;
      }
      ++listed;
      for (int k = 0; k <= 8; ++k) {
        const Vec3d p = a + (k / 8.0) * (b - a);
        const double r_sq = radius * radius;
        // Beyond the accepting radius the distance is exact, as the tree's.
        const auto exact = tree.nearest_bounded(p, 0.0, r_sq);
        const auto mine = local.nearest_bounded(p, 0.0, r_sq);
        CHECK(mine.squared_distance == exact.squared_distance);
        // With early acceptance, an upper bound, never above the accepting radius when the tree found one.
        const auto early = local.nearest_bounded(p, r_sq, r_sq);
        CHECK((early.squared_distance <= r_sq) == (exact.squared_distance <= r_sq));
        CHECK(early.squared_distance >= exact.squared_distance);
        if (early.slot != AabbTree::kNoSlot) CHECK(tree.slot_near_all(early.slot, std::span(&p, 1), r_sq));
      }
      const std::array<Vec3d, 2> ends{a, b};
      CHECK(local.one_triangle_near_all(ends, radius * radius) ==
            tree.one_triangle_near_all(ends, radius * radius));
    }
    CHECK(listed > 50);  // both cases occur
    CHECK(overflowed > 0);
  }
}
