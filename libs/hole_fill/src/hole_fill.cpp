#include <mr/hole_fill/hole_fill.h>

#include "boundary_loops.h"
#include "filled_surface.h"
#include "patch.h"

#include <mr/core/weld.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <unordered_map>

namespace mr::hole_fill {

const char* to_string(HoleOutcome outcome) {
  switch (outcome) {
    case HoleOutcome::filled: return "filled";
    case HoleOutcome::too_long: return "too_long";
    case HoleOutcome::too_wide: return "too_wide";
    case HoleOutcome::failed: return "failed";
  }
  return "?";
}

std::size_t HoleFillResult::filled() const {
  return std::size_t(std::count_if(holes.begin(), holes.end(),
                                   [](const HoleReport& h) { return h.outcome == HoleOutcome::filled; }));
}

namespace {

using detail::BorderLoop;
using detail::GlobalPatch;
using detail::HoleNeighbourhood;
using detail::PatchMethod;
using detail::Triangulator;

// The full search is cubic in the loop's length: beyond this it is not tried.
constexpr std::size_t kFullSearchMaxLoop = 400;

using VertexFaces = std::vector<std::vector<std::uint32_t>>;

VertexFaces faces_around_vertices(const TriangleSoup& soup) {
  VertexFaces around(soup.positions.size());
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    for (Index v : t) around[v].push_back(f);
  }
  return around;
}

// The loop and `rings` rings of faces around it, in local indices (the
// loop first), with the map from local to surface indices.
struct LocalHole {
  HoleNeighbourhood hole;
  std::vector<Index> to_global;
};

LocalHole gather_neighbourhood(const TriangleSoup& soup, const VertexFaces& around, const BorderLoop& loop,
                               int rings) {
  LocalHole local;
  std::unordered_map<Index, Index> to_local;
  auto local_of = [&](Index v) {
    auto [it, added] = to_local.emplace(v, Index(local.to_global.size()));
    if (added) local.to_global.push_back(v);
    return it->second;
  };
  for (Index v : loop.vertices) local_of(v);
  local.hole.loop_size = loop.vertices.size();
  for (Index v : loop.opposite) local.hole.opposite.push_back(soup.positions[v]);
  std::vector<std::uint8_t> taken(soup.triangles.size(), 0);
  std::size_t frontier_begin = 0;
  for (int ring = 0; ring < rings; ++ring) {
    const std::size_t frontier_end = local.to_global.size();
    for (std::size_t i = frontier_begin; i < frontier_end; ++i)
      for (std::uint32_t f : around[local.to_global[i]]) {
        if (taken[f]) continue;
        taken[f] = 1;
        const Triangle& t = soup.triangles[f];
        local.hole.ring.push_back({local_of(t[0]), local_of(t[1]), local_of(t[2])});
      }
    frontier_begin = frontier_end;
  }
  for (Index v : local.to_global) local.hole.positions.push_back(soup.positions[v]);
  return local;
}

// The methods tried in turn: the one asked for, then others that may avoid
// what made it fail (a different triangulation; without or with new
// vertices, which can bend the patch away from a nearby part).
std::vector<PatchMethod> methods_to_try(const HoleFillOptions& o, std::size_t loop_size) {
  const bool refine = o.density == Density::keep;
  std::vector<PatchMethod> all = {
      {Triangulator::delaunay_3d, refine, o.fairing},
      {Triangulator::plane_2d, refine, o.fairing},
      {Triangulator::full_search, refine, o.fairing},
      {Triangulator::delaunay_3d, !refine, refine ? Fairing::none : Fairing::tangent},
      {Triangulator::full_search, !refine, refine ? Fairing::none : Fairing::tangent},
      {Triangulator::delaunay_3d, true, Fairing::curvature},
  };
  std::vector<PatchMethod> out;
  for (const PatchMethod& m : all) {
    if (m.triangulator == Triangulator::full_search && loop_size > kFullSearchMaxLoop) continue;
    const bool seen = std::any_of(out.begin(), out.end(), [&](const PatchMethod& n) {
      return n.triangulator == m.triangulator && n.refine == m.refine && (!m.refine || n.fairing == m.fairing);
    });
    if (!seen) out.push_back(m);
  }
  return out;
}

std::string method_name(const PatchMethod& m) {
  std::string name = m.triangulator == Triangulator::delaunay_3d   ? "liepa_delaunay"
                     : m.triangulator == Triangulator::full_search ? "liepa_full"
                                                                   : "plane_cdt";
  if (m.refine) name += m.fairing == Fairing::none ? "+refine" : "+refine+fair" + std::to_string(int(m.fairing));
  return name;
}

// The patch in surface indices, its new vertices on the output grid.
GlobalPatch to_global(const detail::Patch& patch, const LocalHole& local, Index first_new, const CoordinateGrid& grid) {
  GlobalPatch out;
  const Index local_count = Index(local.to_global.size());
  for (const Vec3d& p : patch.new_positions) out.new_positions.push_back(grid.nearest(p));
  for (const Triangle& t : patch.faces) {
    Triangle g{};
    for (int i = 0; i < 3; ++i) g[i] = t[i] < local_count ? local.to_global[t[i]] : first_new + (t[i] - local_count);
    out.faces.push_back(g);
  }
  return out;
}

struct HoleWork {
  BorderLoop loop;
  LocalHole local;
  std::vector<PatchMethod> methods;
  std::optional<detail::Patch> first;  ///< the first method's patch, made in parallel
  HoleReport report;
};

double diameter(const TriangleSoup& soup, const BorderLoop& loop) {
  Vec3d lo = soup.positions[loop.vertices.front()], hi = lo;
  for (Index v : loop.vertices) {
    lo = lo.cwiseMin(soup.positions[v]);
    hi = hi.cwiseMax(soup.positions[v]);
  }
  return (hi - lo).norm();
}

HoleOutcome selection(const HoleReport& r, const HoleFillOptions& o) {
  if (o.max_boundary > 0 && r.border_edges > o.max_boundary) return HoleOutcome::too_long;
  if (r.diameter > o.max_diameter) return HoleOutcome::too_wide;
  return HoleOutcome::failed;  // to be filled
}

// Tries the methods of `work` in turn until the surface accepts a patch.
void fill_one(HoleWork& work, detail::FilledSurface& surface, const HoleFillOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t m = 0; m < work.methods.size(); ++m) {
    std::optional<detail::Patch> patch =
        m == 0 ? std::move(work.first) : detail::make_patch(work.local.hole, work.methods[m]);
    ++work.report.attempts;
    if (!patch) continue;
    const GlobalPatch global = to_global(*patch, work.local, Index(surface.num_vertices()), o.grid);
    if (!surface.refusal(global).empty()) continue;
    surface.add(global);
    work.report.outcome = HoleOutcome::filled;
    work.report.method = method_name(work.methods[m]);
    work.report.patch_faces = global.faces.size();
    work.report.patch_vertices = global.new_positions.size();
    break;
  }
  work.report.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

HoleFillResult fill_holes(const TriangleSoup& input, const HoleFillOptions& options) {
  TriangleSoup welded = weld_identical_vertices(input);
  const VertexFaces around = faces_around_vertices(welded);
  std::vector<HoleWork> work;
  for (BorderLoop& loop : detail::find_border_loops(welded)) {
    HoleWork w;
    w.report.border_edges = loop.vertices.size();
    w.report.diameter = diameter(welded, loop);
    w.report.outcome = selection(w.report, options);
    w.loop = std::move(loop);
    work.push_back(std::move(w));
  }
  const int rings = int(options.fairing) + 1;
  tbb::parallel_for(std::size_t(0), work.size(), [&](std::size_t i) {
    HoleWork& w = work[i];
    if (w.report.outcome != HoleOutcome::failed) return;
    const auto start = std::chrono::steady_clock::now();
    w.local = gather_neighbourhood(welded, around, w.loop, rings);
    w.methods = methods_to_try(options, w.loop.vertices.size());
    w.first = detail::make_patch(w.local.hole, w.methods.front());
    w.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  HoleFillResult result;
  result.input_faces = welded.triangles.size();
  detail::FilledSurface surface(std::move(welded));
  for (HoleWork& w : work) {
    if (w.report.outcome == HoleOutcome::failed) fill_one(w, surface, options);
    result.holes.push_back(w.report);
  }
  result.surface = surface.surface();
  return result;
}

}  // namespace mr::hole_fill
