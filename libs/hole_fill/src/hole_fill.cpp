#include <mr/hole_fill/hole_fill.h>

#include "boundary_loops.h"
#include "filled_surface.h"
#include "islands.h"
#include "mesh_keys.h"
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
    case HoleOutcome::filled:
      return "filled";
    case HoleOutcome::too_long:
      return "too_long";
    case HoleOutcome::too_wide:
      return "too_wide";
    case HoleOutcome::failed:
      return "failed";
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
using detail::Hole;
using detail::HoleNeighbourhood;
using detail::PatchMethod;
using detail::Triangulator;

using VertexFaces = std::vector<std::vector<std::uint32_t>>;

VertexFaces faces_around_vertices(const TriangleSoup& soup) {
  VertexFaces around(soup.positions.size());
  for (std::uint32_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    if (detail::repeats_a_vertex(t)) continue;
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

LocalHole gather_neighbourhood(const TriangleSoup& soup, const VertexFaces& around, const Hole& hole,
                               int rings) {
  const BorderLoop& loop = hole.outer;
  LocalHole local;
  std::unordered_map<Index, Index> to_local;
  auto local_of = [&](Index v) {
    auto [it, added] = to_local.emplace(v, Index(local.to_global.size()));
    if (added) local.to_global.push_back(v);
    return it->second;
  };
  for (Index v : loop.vertices) local_of(v);
  local.hole.loop_size = loop.vertices.size();
  if (!hole.islands.empty()) {
    for (const BorderLoop& island : hole.islands) {
      for (Index v : island.vertices) local_of(v);
      local.hole.island_sizes.push_back(island.vertices.size());
    }
    const detail::HolePlane plane = detail::hole_plane(soup, loop);
    for (Index v : local.to_global) local.hole.projected.push_back(plane.project(soup.positions[v]));
  }
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
std::vector<PatchMethod> methods_to_try(const HoleFillOptions& o, const Hole& hole) {
  const std::size_t loop_size = hole.outer.vertices.size();
  const bool refine = o.density == Density::keep;
  if (!hole.islands.empty())  // triangulated in the plane; refined and faired or not
    return {{Triangulator::plane_2d, refine, o.fairing},
            {Triangulator::plane_2d, !refine, refine ? Fairing::none : Fairing::tangent}};
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
    if (m.triangulator == Triangulator::full_search && loop_size > detail::kCubicSearchMaxLoop) continue;
    const bool seen = std::any_of(out.begin(), out.end(), [&](const PatchMethod& n) {
      return n.triangulator == m.triangulator && n.refine == m.refine &&
             (!m.refine || n.fairing == m.fairing);
    });
    if (!seen) out.push_back(m);
  }
  return out;
}

std::string method_name(const PatchMethod& m) {
  std::string name = m.triangulator == Triangulator::delaunay_3d   ? "liepa_delaunay"
                     : m.triangulator == Triangulator::full_search ? "liepa_full"
                                                                   : "plane_cdt";
  if (m.refine)
    name += m.fairing == Fairing::none ? "+refine" : "+refine+fair" + std::to_string(int(m.fairing));
  return name;
}

// The patch in surface indices, its new vertices on the output grid.
GlobalPatch to_global(const detail::Patch& patch, const LocalHole& local, Index first_new,
                      const CoordinateGrid& grid) {
  GlobalPatch out;
  const Index local_count = Index(local.to_global.size());
  for (const Vec3d& p : patch.new_positions) out.new_positions.push_back(grid.nearest(p));
  for (const Triangle& t : patch.faces) {
    Triangle g{};
    for (int i = 0; i < 3; ++i)
      g[i] = t[i] < local_count ? local.to_global[t[i]] : first_new + (t[i] - local_count);
    out.faces.push_back(g);
  }
  return out;
}

struct HoleWork {
  Hole hole;
  bool prepared = false;
  LocalHole local;
  std::vector<PatchMethod> methods;
  std::optional<detail::Patch> first;  ///< the first method's patch, made in parallel
  HoleReport report;
};

double diameter(const TriangleSoup& soup, const BorderLoop& loop) {  // of the loop's box
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
    if (!patch) {
      work.report.why = "no triangulation found";
      continue;
    }
    const GlobalPatch global = to_global(*patch, work.local, Index(surface.num_vertices()), o.grid);
    work.report.why = surface.refusal(global);
    if (!work.report.why.empty()) continue;
    surface.add(global);
    work.report.outcome = HoleOutcome::filled;
    work.report.method = method_name(work.methods[m]);
    work.report.patch_faces = global.faces.size();
    work.report.patch_vertices = global.new_positions.size();
    break;
  }
  work.report.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

HoleWork make_work(const TriangleSoup& welded, Hole hole, const HoleFillOptions& options) {
  HoleWork w;
  w.report.border_edges = hole.outer.vertices.size();
  for (const BorderLoop& island : hole.islands) w.report.border_edges += island.vertices.size();
  w.report.islands = hole.islands.size();
  w.report.diameter = diameter(welded, hole.outer);
  w.report.outcome = selection(w.report, options);
  w.hole = std::move(hole);
  return w;
}

// The neighbourhood, the methods and the first method's patch: the part
// of the work that needs no other hole (run in parallel).
void prepare(HoleWork& w, const TriangleSoup& welded, const VertexFaces& around,
             const HoleFillOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  w.local = gather_neighbourhood(welded, around, w.hole, int(options.fairing) + 1);
  w.methods = methods_to_try(options, w.hole);
  w.first = detail::make_patch(w.local.hole, w.methods.front());
  w.prepared = true;
  w.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Holes prepared at once when a run may stop at its first open hole: a
// few per thread.
constexpr std::size_t kPrepareBatch = 16;

// Prepares, in parallel, the holes to fill among work[from, from + count);
// returns the end of that range.
std::size_t prepare_batch(std::vector<HoleWork>& work, std::size_t from, std::size_t count,
                          const TriangleSoup& welded, const VertexFaces& around,
                          const HoleFillOptions& options) {
  const std::size_t to = std::min(work.size(), from + count);
  tbb::parallel_for(from, to, [&](std::size_t i) {
    if (work[i].report.outcome == HoleOutcome::failed && !work[i].prepared)
      prepare(work[i], welded, around, options);
  });
  return to;
}

}  // namespace

HoleFillResult fill_holes(const TriangleSoup& input, const HoleFillOptions& options) {
  TriangleSoup welded = weld_identical_vertices(input);
  HoleFillResult result;
  result.input_faces = welded.triangles.size();
  detail::BorderLoops border = detail::find_border_loops(welded);
  result.open_border_edges = border.open_edges;
  if (border.loops.empty()) {  // nothing to fill, nothing to test patches against
    result.surface = std::move(welded);
    return result;
  }
  const VertexFaces around = faces_around_vertices(welded);
  std::vector<HoleWork> work;
  for (Hole& hole : detail::group_islands(welded, std::move(border.loops)))
    work.push_back(make_work(welded, std::move(hole), options));
  // Prepared in parallel, all at once or, where the first hole left open
  // ends the run, a batch at a time so the rest is not prepared in vain.
  const std::size_t batch = options.stop_at_first_failure ? kPrepareBatch : work.size();
  std::size_t prepared_to = 0;
  detail::FilledSurface surface(welded);
  // Accepted in order; a hole with islands that no patch fills is retried
  // as separate loops, appended to the work.
  for (std::size_t i = 0; i < work.size(); ++i) {
    if (i == prepared_to) prepared_to = prepare_batch(work, i, batch, welded, around, options);
    if (work[i].report.outcome == HoleOutcome::failed) {
      if (!work[i].prepared) prepare(work[i], welded, around, options);
      fill_one(work[i], surface, options);
    }
    if (work[i].report.outcome == HoleOutcome::failed && !work[i].hole.islands.empty()) {
      Hole joined = std::move(work[i].hole);
      work.push_back(make_work(welded, {std::move(joined.outer), {}}, options));
      for (BorderLoop& island : joined.islands)
        work.push_back(make_work(welded, {std::move(island), {}}, options));
      continue;
    }
    result.holes.push_back(work[i].report);
    if (options.stop_at_first_failure && work[i].report.outcome != HoleOutcome::filled) break;
  }
  result.surface = std::move(surface).release();
  return result;
}

}  // namespace mr::hole_fill
