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

}  // namespace

TEST_CASE("box grid queries agree with brute force through inserts, moves, erases and rebuilds", "[aabb]") {
  std::mt19937_64 rng(7);
  BoxGrid grid(Vec3d(-2.0, -2.0, -2.0), 0.25);
  std::vector<Box> boxes(3000);
  std::uniform_int_distribution<std::size_t> pick(0, boxes.size() - 1);
  std::uniform_int_distribution<int> action(0, 9);
  std::vector<std::uint32_t> found;
  std::size_t nonempty = 0;
  for (int step = 0; step < 40000; ++step) {
    const std::size_t id = pick(rng);
    const int a = action(rng);
    if (a < 6) {  // insert, or move an inserted one
      boxes[id] = random_box(rng);
      grid.insert(static_cast<std::uint32_t>(id), boxes[id].lo, boxes[id].hi);
    } else if (a < 8) {
      boxes[id].live = false;
      grid.erase(static_cast<std::uint32_t>(id));
    } else {  // a query, sometimes exactly on a box's face
      Box query = random_box(rng);
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
  CHECK(nonempty > 1000);
}
