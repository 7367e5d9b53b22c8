#include "test_support.h"

#include <mr/winding_number/winding_number.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

namespace mr {
namespace {

// Closed UV sphere of radius 1 about the origin, outward triangles; the poles
// are fans, so no triangle is degenerate. 2 * rings * (segments - 1) triangles.
TriangleSoup uv_sphere(int rings, int segments) {
  TriangleSoup soup;
  soup.positions.emplace_back(0, 0, 1);
  for (int i = 1; i < segments; ++i) {
    const double theta = std::numbers::pi * i / segments;
    for (int j = 0; j < rings; ++j) {
      const double phi = 2 * std::numbers::pi * j / rings;
      soup.positions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                  std::cos(theta));
    }
  }
  soup.positions.emplace_back(0, 0, -1);
  const auto ring_vertex = [&](int i, int j) {
    return static_cast<Index>(1 + (i - 1) * rings + (j % rings));
  };
  const auto south = static_cast<Index>(soup.positions.size() - 1);
  for (int j = 0; j < rings; ++j) {
    soup.triangles.push_back({0, ring_vertex(1, j), ring_vertex(1, j + 1)});
    soup.triangles.push_back({south, ring_vertex(segments - 1, j + 1), ring_vertex(segments - 1, j)});
    for (int i = 1; i + 1 < segments; ++i) {
      soup.triangles.push_back({ring_vertex(i, j), ring_vertex(i + 1, j), ring_vertex(i + 1, j + 1)});
      soup.triangles.push_back({ring_vertex(i, j), ring_vertex(i + 1, j + 1), ring_vertex(i, j + 1)});
    }
  }
  return soup;
}

TriangleSoup inverted(TriangleSoup soup) {
  for (Triangle& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

// Checks exact and fast evaluation at q against `expected`.
void check_both(const TriangleSoup& soup, const Vec3d& q, double expected) {
  INFO("query " << q.transpose());
  CHECK(winding_number_exact(soup, q) == Approx(expected).margin(1e-9));
  CHECK(WindingNumberTree(soup).evaluate(q) == Approx(expected).margin(1e-2));
}

}  // namespace

TEST_CASE("solid angle of an octant triangle is pi/2, signed by side", "[winding]") {
  const Vec3d a(1, 0, 0), b(0, 1, 0), c(0, 0, 1);
  CHECK(signed_solid_angle(a, b, c, Vec3d::Zero()) == Approx(std::numbers::pi / 2));
  CHECK(signed_solid_angle(a, c, b, Vec3d::Zero()) == Approx(-std::numbers::pi / 2));
  CHECK(signed_solid_angle(a, b, c, Vec3d(1e8, 1e8, 1e8)) == Approx(0).margin(1e-12));
}

TEST_CASE("winding number of a cube is 1 inside and 0 outside", "[winding]") {
  const TriangleSoup cube = test::cube_soup();
  for (const Vec3d& q : {Vec3d(0.5, 0.5, 0.5), Vec3d(0.1, 0.2, 0.9), Vec3d(0.99, 0.01, 0.5)})
    check_both(cube, q, 1.0);
  for (const Vec3d& q : {Vec3d(2, 0.5, 0.5), Vec3d(-1, -1, -1), Vec3d(0.5, 0.5, 1.05), Vec3d(100, 0, 0)})
    check_both(cube, q, 0.0);
}

TEST_CASE("an inverted cube has winding number -1 inside", "[winding]") {
  const TriangleSoup cube = inverted(test::cube_soup());
  check_both(cube, Vec3d(0.5, 0.5, 0.5), -1.0);
  check_both(cube, Vec3d(0.2, 0.7, 0.3), -1.0);
  check_both(cube, Vec3d(3, 3, 3), 0.0);
}

TEST_CASE("two overlapping cubes give 2 in the overlap", "[winding]") {
  TriangleSoup soup = test::cube_soup(0, 1);
  soup.append(test::cube_soup(0.5, 1.5));
  check_both(soup, Vec3d(0.75, 0.75, 0.75), 2.0);
  check_both(soup, Vec3d(0.25, 0.25, 0.25), 1.0);
  check_both(soup, Vec3d(1.25, 1.25, 1.25), 1.0);
  check_both(soup, Vec3d(1.25, 0.25, 0.25), 0.0);
}

TEST_CASE("an open cube gives fractional winding numbers inside", "[winding]") {
  TriangleSoup cube = test::cube_soup();
  cube.triangles.erase(cube.triangles.begin() + 2, cube.triangles.begin() + 4);  // the z = 1 face
  // From the centre the missing face subtends a sixth of the sphere.
  check_both(cube, Vec3d(0.5, 0.5, 0.5), 5.0 / 6.0);
  const WindingNumberTree tree(cube);
  for (const Vec3d& q :
       {Vec3d(0.5, 0.5, 0.95), Vec3d(0.1, 0.1, 0.1), Vec3d(0.9, 0.5, 0.99), Vec3d(0.5, 0.5, 0.6)}) {
    INFO("query " << q.transpose());
    const double exact = winding_number_exact(cube, q);
    CHECK(exact > 0.0);
    CHECK(exact < 1.0);
    CHECK(tree.evaluate(q) == Approx(exact).margin(1e-2));
  }
  // Just above the hole the value stays below 1/2, just below it above 1/2.
  CHECK(winding_number_exact(cube, Vec3d(0.5, 0.5, 1.01)) < 0.5);
  CHECK(winding_number_exact(cube, Vec3d(0.5, 0.5, 0.99)) > 0.5);
}

TEST_CASE("fast winding numbers match the exact sum on a 20k-triangle sphere", "[winding][slow]") {
  const TriangleSoup sphere = uv_sphere(160, 64);
  REQUIRE(sphere.num_triangles() >= 20000);
  const WindingNumberTree tree(sphere);
  const double min_distance = 0.01 * bounding_box_diagonal(sphere);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  std::vector<Vec3d> queries;
  while (queries.size() < 2000) {
    const Vec3d q(coordinate(rng), coordinate(rng), coordinate(rng));
    if (std::abs(q.norm() - 1.0) > min_distance) queries.push_back(q);
  }
  const std::vector<double> fast = tree.evaluate(queries);
  double max_error = 0.0;
  int inside = 0;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const double exact = winding_number_exact(sphere, queries[i]);
    CHECK(exact == Approx(queries[i].norm() < 1.0 ? 1.0 : 0.0).margin(1e-6));
    max_error = std::max(max_error, std::abs(fast[i] - exact));
    inside += queries[i].norm() < 1.0;
  }
  CHECK(inside > 100);
  CHECK(max_error < 1e-2);
}

TEST_CASE("batched evaluation equals single evaluation bit for bit", "[winding]") {
  const TriangleSoup sphere = uv_sphere(64, 32);
  const WindingNumberTree tree(sphere);
  std::vector<Vec3d> queries;
  for (int i = 0; i < 5000; ++i)
    queries.emplace_back(std::sin(i * 0.37) * 1.3, std::cos(i * 0.11), 0.001 * i - 2.5);
  const std::vector<double> batch = tree.evaluate(queries);
  REQUIRE(batch.size() == queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) REQUIRE(batch[i] == tree.evaluate(queries[i]));
  const WindingNumberTree rebuilt(sphere);
  for (std::size_t i = 0; i < queries.size(); i += 97) REQUIRE(rebuilt.evaluate(queries[i]) == batch[i]);
}

TEST_CASE("duplicated faces double the winding number", "[winding]") {
  TriangleSoup soup = test::cube_soup();
  soup.append(test::cube_soup());
  check_both(soup, Vec3d(0.5, 0.5, 0.5), 2.0);
  check_both(soup, Vec3d(0.3, 0.8, 0.1), 2.0);
  check_both(soup, Vec3d(-0.5, 0.5, 0.5), 0.0);
}

TEST_CASE("degenerate triangles add nothing and never give NaN", "[winding]") {
  TriangleSoup soup = test::cube_soup();
  const TriangleSoup clean = soup;
  soup.positions.emplace_back(0.5, 0.0, 0.0);  // on edge 0-1
  soup.positions.emplace_back(0.3, 0.3, 0.3);
  const auto mid = static_cast<Index>(soup.positions.size() - 2), inner = mid + 1;
  soup.triangles.push_back({0, 1, mid});        // collinear
  soup.triangles.push_back({inner, inner, 2});  // repeated index
  soup.triangles.push_back({inner, inner, inner});
  for (const Vec3d& q : {Vec3d(0.5, 0.5, 0.5), Vec3d(0.3, 0.3, 0.31), Vec3d(2, 2, 2)}) {
    CHECK(winding_number_exact(soup, q) == winding_number_exact(clean, q));
    CHECK(WindingNumberTree(soup).evaluate(q) == Approx(WindingNumberTree(clean).evaluate(q)).margin(1e-12));
  }
  // Queries on a vertex, an edge, a face and on the degenerate triangles stay finite.
  const WindingNumberTree tree(soup);
  for (const Vec3d& q :
       {Vec3d(0, 0, 0), Vec3d(0.5, 0, 0), Vec3d(0.5, 0.5, 0), Vec3d(0.3, 0.3, 0.3), Vec3d(1, 1, 1)}) {
    CHECK(std::isfinite(winding_number_exact(soup, q)));
    CHECK(std::isfinite(tree.evaluate(q)));
  }
}

TEST_CASE("an empty soup has winding number 0 everywhere", "[winding]") {
  const TriangleSoup empty;
  CHECK(winding_number_exact(empty, Vec3d(1, 2, 3)) == 0.0);
  const WindingNumberTree tree(empty);
  CHECK(tree.evaluate(Vec3d(1, 2, 3)) == 0.0);
  CHECK(tree.evaluate(std::vector<Vec3d>{}).empty());
}

}  // namespace mr
