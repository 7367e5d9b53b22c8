#include <mr/tetmesh/insertion.h>

#include "coplanar_polygons.h"
#include "inserter_keys.h"
#include "triangle_inserter.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

namespace mr::tetmesh {
namespace {

// Copies of one triangle (the same three mesh vertices, in either order)
// embed as the same faces: only the first is inserted, and the others' ids
// are added where it landed. CAD soups repeat faces by the thousand, and
// each copy would otherwise walk and test every tet of its plane again.
class Copies {
 public:
  /// The id of the first triangle on these corners, or `id` when it is the first.
  std::uint32_t first_on(Index a, Index b, Index c, std::uint32_t id) {
    std::array<Index, 3> key{a, b, c};
    std::sort(key.begin(), key.end());
    const auto [it, inserted] = first_.try_emplace(key, id);
    if (!inserted) copies_[it->second].push_back(id);
    return it->second;
  }

  std::size_t count() const {
    std::size_t n = 0;
    for (const auto& [first, ids] : copies_) n += ids.size();
    return n;
  }

  /// Adds the copies' ids to every face that carries their first's id.
  void mark(Mesh& mesh) const {
    if (copies_.empty()) return;
    for (Index t = 0; t < mesh.tet_slots(); ++t) {
      if (!mesh.tet_alive(t)) continue;
      for (int k = 0; k < 4; ++k) {
        const auto ids = mesh.surface_ids(t, k);
        const Index n = mesh.neighbour(t, k);
        if (ids.empty() || (n != kNoTet && n < t)) continue;  // each face once
        std::vector<std::uint32_t> all(ids.begin(), ids.end());
        for (const std::uint32_t id : ids) {
          const auto found = copies_.find(id);
          if (found != copies_.end()) all.insert(all.end(), found->second.begin(), found->second.end());
        }
        if (all.size() != ids.size()) mesh.set_surface_ids(t, k, all);
      }
    }
  }

 private:
  std::map<std::array<Index, 3>, std::uint32_t> first_;
  std::map<std::uint32_t, std::vector<std::uint32_t>> copies_;
};

// Triangles that may merge with coplanar neighbours into one polygon: not
// skipped, three distinct corners, and no copy anywhere (copies are
// inserted once and marked afterwards, see Copies).
std::vector<char> mergeable(std::span<const std::array<Index, 3>> triangles, std::span<const char> skip,
                            const InsertionOptions& options) {
  std::vector<char> eligible(triangles.size(), 0);
  if (!options.merge_coplanar) return eligible;
  std::map<std::array<Index, 3>, std::size_t> uses;
  for (const auto& f : triangles) ++uses[detail::sorted_corners(f)];
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& f = triangles[i];
    const bool distinct = f[0] != f[1] && f[1] != f[2] && f[2] != f[0];
    eligible[i] = (skip.empty() || skip[i] == 0) && distinct && uses[detail::sorted_corners(f)] == 1;
  }
  return eligible;
}

// Throws InsertionTooCostly once the mesh has more than `max_tets` tets, or
// once it is on course to have four times as many: after a thousandth of the
// triangles (at least 32), the growth so far carried on at the same rate to
// all of them. The long slivers of a CAD model's kept input
// (manifold/Generic_Twin) cut hundreds of thousands of tets in the first
// hundred triangles; waiting for the budget itself cost seconds the rebuild
// needs. A growth on course for 32 times the budget is stopped after 8
// triangles already: Generic_Twin right with every vertex jittered grew by
// 66,000 tets with its first triangle and passed its budget of 2.7M after
// 19 (2.9M tets, most of its 44 s before the outer hull). To be stopped so
// early, each of the first triangles must have made thousands of tets on
// average (32 times a budget of 64 a face), where a few dozen is usual.
// In random order the triangles done are a fair sample of all, and the
// growth per triangle only rises as the mesh fills: after a hundredth of
// them, the rate of the second half of those done, carried on to the rest,
// stops a course for 1.5 times the budget too. With only the average rate
// and the factor 4 of file order, thingi10k/1514499 with every vertex
// jittered ran into its budget after 5,937 of 19,954 triangles, and the
// band after it spent 79 s inserting and then more than 120 s on the
// surface (45 s for the whole repair in file order, whose first triangles
// had shown the course at once).
// A projection of the final tet count past its multiple of the budget.
struct Overrun {
  double factor;
  double projected;
};

// The first of the rules above that fires, if any.
std::optional<Overrun> projected_overrun(std::span<const std::size_t> tets_after, std::size_t tets_before,
                                         std::size_t n, std::size_t max_tets, bool random_order) {
  constexpr double kProjectedOver = 4.0;
  constexpr double kProjectedFarOver = 32.0;
  constexpr double kSampledOver = 1.5;
  constexpr std::size_t kEarliest = 8;
  const std::size_t done = tets_after.size();
  const auto tets = static_cast<double>(tets_after.back());
  const double budget = static_cast<double>(max_tets);
  const double grown = tets - static_cast<double>(tets_before);
  const double projected = static_cast<double>(tets_before) + grown * static_cast<double>(n) / double(done);
  if (done >= kEarliest && projected > kProjectedFarOver * budget)
    return Overrun{kProjectedFarOver, projected};
  if (done >= std::max<std::size_t>(32, n / 1000) && projected > kProjectedOver * budget)
    return Overrun{kProjectedOver, projected};
  if (!random_order || done < std::max<std::size_t>(32, n / 100)) return std::nullopt;
  const std::size_t half = done / 2;
  const double recent_rate = (tets - static_cast<double>(tets_after[half - 1])) / double(done - half);
  const double sampled = tets + recent_rate * static_cast<double>(n - done);
  if (sampled > kSampledOver * budget) return Overrun{kSampledOver, sampled};
  return std::nullopt;
}

void check_budget(std::span<const std::size_t> tets_after, std::size_t tets_before, std::size_t n,
                  std::size_t max_tets, bool random_order) {
  const std::size_t done = tets_after.size();
  const std::size_t tets = tets_after.back();
  const auto after = [&] {
    return std::to_string(tets) + " tets after " + std::to_string(done) + " of " + std::to_string(n) +
           " triangles";
  };
  if (tets > max_tets)
    throw InsertionTooCostly("insertion: more than " + std::to_string(max_tets) + ": " + after());
  if (done >= n) return;
  const std::optional<Overrun> overrun =
      projected_overrun(tets_after, tets_before, n, max_tets, random_order);
  if (!overrun) return;
  std::ostringstream why;
  why << "insertion: on course for " << std::llround(overrun->projected) << " tets, more than "
      << overrun->factor << " times its budget of " << max_tets << ": " << after();
  throw InsertionTooCostly(why.str());
}

// Triangles may be inserted in a seeded random order, as randomized
// incremental constructions are (InsertionOptions::random_order). In file order, neighbours follow each other
// and each plane cuts again the thin tets its neighbour's cut just made near it: thingi10k/88566 made 290,571
// cut points in 32 s that way, 103,250 in 9.9 s shuffled (1514499: 334,072 -> 180,475; trimesh/boolean
// 166,352 -> 139,489). Fisher-Yates on a xorshift generator: the same order on every platform and thread
// count.
std::vector<std::size_t> insertion_order(std::size_t n, bool random) {
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t(0));
  if (!random) return order;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (std::size_t i = n; i > 1; --i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    std::swap(order[i - 1], order[state % i]);
  }
  return order;
}

}  // namespace

InsertionStats insert_triangles(Mesh& mesh, const TriangleSoup& input, std::span<const Index> input_vertex,
                                std::span<const char> skip, const Logger& logger,
                                const InsertionOptions& options) {
  if (input_vertex.size() != input.positions.size()) {
    throw UsageError("insert_triangles: the vertex map does not match the input");
  }
  if (!skip.empty() && skip.size() != input.triangles.size()) {
    throw UsageError("insert_triangles: the skip list does not match the input");
  }
  const std::size_t n = input.triangles.size();
  std::vector<std::array<Index, 3>> triangles(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& f = input.triangles[i];
    triangles[i] = {input_vertex[f[0]], input_vertex[f[1]], input_vertex[f[2]]};
  }
  const detail::CoplanarGrouping grouping = detail::group_coplanar_triangles(
      mesh, triangles, mergeable(triangles, skip, options), detail::TriangleInserter::kMaxCorners);

  detail::TriangleInserter inserter(mesh, options.max_exact_bits, options.snap_distance,
                                    options.settle_cut_points);
  Copies copies;
  InsertionStats stats;
  const std::size_t tets_before = mesh.num_tets();
  stats.marked_as.resize(n);
  std::vector<std::size_t> polygon_at(n, 0);
  for (std::size_t p = 0, i = 0; i < n; ++i)
    if (grouping.polygon_of[i] == i) polygon_at[i] = p++;
  const std::vector<std::size_t> order = insertion_order(n, options.random_order);
  std::vector<std::size_t> tets_after;  // tets after each step, for the budget
  tets_after.reserve(n);
  const std::size_t report_every = std::max<std::size_t>(1, n / 100);
  for (std::size_t step = 0; step < n; ++step) {
    const std::size_t i = order[step];
    const auto id = static_cast<std::uint32_t>(i);
    stats.marked_as[i] = id;
    if (!skip.empty() && skip[i] != 0) {
      ++stats.skipped;
      continue;
    }
    const std::uint32_t group = grouping.polygon_of[i];
    if (group == detail::CoplanarGrouping::kNotGrouped) {
      const auto& [a, b, c] = triangles[i];
      if (copies.first_on(a, b, c, id) == id) inserter.insert(triangles[i], id);
    } else if (group == id) {
      const auto& polygon = grouping.polygons[polygon_at[i]];
      inserter.insert(polygon.corners, id);
      if (polygon.corners.size() > 3) ++stats.polygons;
    } else {
      stats.marked_as[i] = group;
      ++stats.merged;
    }
    if (step % report_every == 0)
      logger.progress("insertion", static_cast<double>(step) / static_cast<double>(n));
    tets_after.push_back(mesh.num_tets());
    if (options.max_tets != 0)
      check_budget(tets_after, tets_before, n, options.max_tets, options.random_order);
  }
  copies.mark(mesh);
  stats.copies = copies.count();
  const detail::InsertionCounters& c = inserter.counters();
  stats.inserted = c.inserted;
  stats.degenerate = c.degenerate;
  stats.cut_tets = c.cut_tets;
  stats.rebuilt_tets = c.rebuilt_tets;
  stats.new_tets = c.new_tets;
  stats.new_vertices = c.new_vertices;
  stats.steiner_points = c.steiner_points;
  stats.eagerly_rounded = c.eagerly_rounded;
  stats.already_faces = c.already_faces;
  stats.snapped_points = c.snapped_points;
  stats.settled_points = c.settled_points;
  stats.vertex_creator = inserter.creators();
  stats.vertex_creator.resize(mesh.vertex_slots(), InsertionStats::kNoCreator);
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    stats.rational_vertices += mesh.vertex_alive(v) && mesh.position(v).is_exact();
  }
  logger.log(LogLevel::debug, "insertion: " + std::to_string(stats.inserted) + " triangles and polygons (" +
                                  std::to_string(stats.merged) + " triangles merged into " +
                                  std::to_string(stats.polygons) + " coplanar polygons, " +
                                  std::to_string(stats.copies) + " copies), " +
                                  std::to_string(stats.new_vertices) + " cut points, " +
                                  std::to_string(stats.rational_vertices) + " still rational");
  return stats;
}

}  // namespace mr::tetmesh
