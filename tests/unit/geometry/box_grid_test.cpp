#include <mr/spatial/box_grid.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

namespace {

using mr::Vec3d;
using mr::spatial::BoxGrid;

struct Box {
  Vec3d lo, hi;
  bool live = false;
};

bool overlap(const Box& a, const Vec3d& lo, const Vec3d& hi) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] < lo[k] || a.lo[k] > hi[k]) return false;
  return true;
}

// Mostly small boxes, some spanning many cells (the grid's oversize list),
// some degenerate (a point, a flat box), some touching the query exactly.
Box random_box(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> where(-1.0, 11.0);
  std::uniform_int_distribution<int> kind(0, 9);
  const Vec3d corner(where(rng), where(rng), where(rng));
  Vec3d size;
  switch (kind(rng)) {
    case 0:
      size = Vec3d::Zero();
      break;
    case 1:
      size = Vec3d(6.0, 5.0, 0.0);
      break;
    default: {
      std::uniform_real_distribution<double> extent(0.0, 0.6);
      size = Vec3d(extent(rng), extent(rng), extent(rng));
    }
  }
  return {corner, corner + size, true};
}

// Random inserts (new boxes, or moves of inserted ones), erases and
// queries, each query compared with brute force; returns how many queries
// had some box to find.
template <typename MakeBox>
std::size_t run_against_brute_force(BoxGrid& grid, std::vector<Box>& boxes, int steps, int inserts,
                                    int erases, MakeBox&& make_box, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> pick(0, boxes.size() - 1);
  std::uniform_int_distribution<int> action(0, 9);
  std::vector<std::uint32_t> found;
  std::size_t nonempty = 0;
  for (int step = 0; step < steps; ++step) {
    const std::size_t id = pick(rng);
    const int a = action(rng);
    if (a < inserts) {
      boxes[id] = make_box(rng);
      grid.insert(static_cast<std::uint32_t>(id), boxes[id].lo, boxes[id].hi);
    } else if (a < inserts + erases) {
      boxes[id].live = false;
      grid.erase(static_cast<std::uint32_t>(id));
    } else {  // a query, sometimes exactly on a box's face
      Box query = make_box(rng);
      if (a == 9 && boxes[id].live) query.lo.x() = boxes[id].hi.x();
      query.hi = query.hi.cwiseMax(query.lo);
      grid.query(query.lo, query.hi, found);
      std::vector<std::uint32_t> expected;
      for (std::size_t i = 0; i < boxes.size(); ++i)
        if (boxes[i].live && overlap(boxes[i], query.lo, query.hi))
          expected.push_back(static_cast<std::uint32_t>(i));
      // The grid may return more than the overlapping boxes (callers test
      // candidates against the geometry), but never repeats and never misses one.
      REQUIRE(std::is_sorted(found.begin(), found.end()));
      REQUIRE(std::adjacent_find(found.begin(), found.end()) == found.end());
      REQUIRE(std::includes(found.begin(), found.end(), expected.begin(), expected.end()));
      for (const std::uint32_t f : found) REQUIRE(boxes[f].live);
      // Unordered: the same ids, in any order, perhaps twice.
      std::vector<std::uint32_t> unordered;
      grid.query_unordered(query.lo, query.hi, unordered);
      std::sort(unordered.begin(), unordered.end());
      unordered.erase(std::unique(unordered.begin(), unordered.end()), unordered.end());
      REQUIRE(unordered == found);
      nonempty += expected.empty() ? 0 : 1;
    }
  }
  return nonempty;
}

}  // namespace

TEST_CASE("box grid queries agree with brute force through inserts, moves, erases and rebuilds", "[aabb]") {
  std::mt19937_64 rng(7);
  BoxGrid grid(Vec3d(-2.0, -2.0, -2.0), 0.25);
  std::vector<Box> boxes(3000);
  CHECK(run_against_brute_force(grid, boxes, 40000, 6, 2, random_box, rng) > 1000);
}

namespace {

// Boxes a thousand times smaller than a cell, crowded into a few cells (a
// surface peeled from crossing sheets), beside cell-sized and larger ones,
// some straddling the halves of a split cell exactly.
Box crowded_box(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<double> near(0.99, 1.01);
  std::uniform_real_distribution<double> tiny(0.0, 1e-4);
  std::uniform_real_distribution<double> anywhere(-1.0, 3.0);
  std::uniform_real_distribution<double> extent(0.0, 0.6);
  const int k = kind(rng);
  if (k < 7) {
    Vec3d corner(near(rng), near(rng), near(rng));
    if (k == 0) corner.x() = 1.0;  // on the line where the cell's halves meet
    return {corner, corner + Vec3d(tiny(rng), tiny(rng), tiny(rng)), true};
  }
  const Vec3d corner(anywhere(rng), anywhere(rng), anywhere(rng));
  return {corner, corner + Vec3d(extent(rng), extent(rng), extent(rng)), true};
}

}  // namespace

TEST_CASE("box grid queries agree with brute force where thousands of tiny boxes crowd a cell", "[aabb]") {
  std::mt19937_64 rng(11);
  BoxGrid grid(Vec3d(-2.0, -2.0, -2.0), 0.5);
  std::vector<Box> boxes(6000);
  for (std::size_t id = 0; id < boxes.size(); ++id) {
    boxes[id] = crowded_box(rng);
    grid.insert(static_cast<std::uint32_t>(id), boxes[id].lo, boxes[id].hi);
  }
  CHECK(run_against_brute_force(grid, boxes, 20000, 3, 1, crowded_box, rng) > 1000);
}
