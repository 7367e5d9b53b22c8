// One pass of each operation over the whole mesh. Candidates are collected
// and sorted first (ties broken by vertex or tet index) and applied one by
// one, so the order never depends on the thread count; smoothing runs in
// parallel on colour classes of vertices that share no tet.

#include "improve_local.h"

#include <mr/tetmesh/incidence.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <optional>
#include <tuple>

namespace mr::tetmesh::improve_detail {
namespace {

struct EdgeCandidate {
  double length;
  Index a, b;
  Index tet;  ///< a tet that had the edge when candidates were collected
};

// Calls visit(a, b, tet) for every edge of the tets that count, with the
// lowest such tet, in increasing (a, b), a < b. Found vertex by vertex from
// the incidence, not from a sorted list of every tet's six edges: that list
// (72 bytes a tet) was the peak of a whole run's memory.
template <class Visit>
void for_each_counted_edge(const Workspace& ws, Visit visit) {
  const Mesh& mesh = ws.mesh;
  const VertexTets incidence(mesh);
  std::vector<std::pair<Index, Index>> ends;  // {b, tet}
  for (Index a = 0; a < mesh.vertex_slots(); ++a) {
    if (!ws.in_focus(a)) continue;
    ends.clear();
    for (const Index t : incidence.of(a)) {
      if (!ws.counts(t)) continue;
      for (const Index b : mesh.tet(t))
        if (b > a && ws.in_focus(b)) ends.emplace_back(b, t);
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t i = 0; i < ends.size(); ++i)
      if (i == 0 || ends[i].first != ends[i - 1].first) visit(a, ends[i].first, ends[i].second);
  }
}

double edge_length(const Mesh& mesh, Index a, Index b) {
  return (mesh.position(a).approx - mesh.position(b).approx).norm();
}

// Edges whose length relative to their target passes `keep`, sorted by length
// (longest first when `longest_first`), ties by vertex index.
template <class Keep>
std::vector<EdgeCandidate> edge_candidates(const Workspace& ws, Keep keep, bool longest_first) {
  std::vector<EdgeCandidate> out;
  for_each_counted_edge(ws, [&](Index a, Index b, Index tet) {
    const double length = edge_length(ws.mesh, a, b);
    if (keep(length, ws.target(a, b))) out.push_back({length, a, b, tet});
  });
  std::sort(out.begin(), out.end(), [&](const EdgeCandidate& x, const EdgeCandidate& y) {
    if (x.length != y.length) return longest_first ? x.length > y.length : x.length < y.length;
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  return out;
}

// Greedy colouring in vertex order of the vertices in focus: no two
// vertices of one colour share a tet.
std::vector<std::vector<Index>> colour_classes(const Workspace& ws, const VertexTets& incidence) {
  const Mesh& mesh = ws.mesh;
  std::vector<int> colour(mesh.vertex_slots(), -1);
  std::vector<std::vector<Index>> classes;
  std::vector<char> used;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (!mesh.vertex_alive(v) || !ws.in_focus(v) || incidence.of(v).empty()) continue;
    used.assign(classes.size() + 1, 0);
    for (const Index t : incidence.of(v)) {
      for (const Index w : mesh.tet(t)) {
        if (colour[w] >= 0) used[colour[w]] = 1;
      }
    }
    const int c = int(std::find(used.begin(), used.end(), 0) - used.begin());
    if (c == int(classes.size())) classes.emplace_back();
    colour[v] = c;
    classes[c].push_back(v);
  }
  return classes;
}

// Whether a corner of the tet is in focus.
bool touches_focus(const Workspace& ws, const Tet& c) {
  return std::any_of(c.begin(), c.end(), [&](Index v) { return ws.in_focus(v); });
}

}  // namespace

std::vector<double> tet_energies(const Workspace& ws, bool driving_only) {
  const Mesh& mesh = ws.mesh;
  std::vector<double> energy(mesh.tet_slots(), 0.0);
  tbb::parallel_for(tbb::blocked_range<Index>(0, Index(mesh.tet_slots()), 1024),
                    [&](const tbb::blocked_range<Index>& range) {
                      for (Index t = range.begin(); t != range.end(); ++t) {
                        if (mesh.tet_alive(t) && (driving_only ? ws.drives(t) : ws.counts(t)))
                          energy[t] = tet_energy(mesh, t);
                      }
                    });
  return energy;
}

// The corners of the tets around a collapsing vertex: the vertices whose
// stars the collapse changes.
std::vector<Index> corners_of(const Mesh& mesh, std::span<const Index> star) {
  std::vector<Index> corners;
  for (const Index t : star)
    for (const Index x : mesh.tet(t)) corners.push_back(x);
  return corners;
}

// Vertices whose star a collapse applied in this batch changed.
class TouchedVertices {
 public:
  explicit TouchedVertices(std::size_t slots) : touched_(slots, 0) {}
  bool operator[](Index v) const { return v < touched_.size() && touched_[v] != 0; }
  void mark(std::span<const Index> vertices) {
    for (const Index x : vertices) {
      if (x >= touched_.size()) touched_.resize(std::size_t(x) + 1, 0);  // a vertex a split made
      if (!touched_[x]) touched_[x] = 1, marked_.push_back(x);
    }
  }
  void clear() {
    for (const Index x : marked_) touched_[x] = 0;
    marked_.clear();
  }

 private:
  std::vector<char> touched_;
  std::vector<Index> marked_;
};

// Collapses a onto b, else b onto a, deciding now; marks what it changed.
bool collapse_either_way(Workspace& ws, Index a, Index b, TouchedVertices& touched) {
  for (const auto& [u, v] : {std::pair(a, b), std::pair(b, a)}) {
    if (const std::optional<CollapsePlan> plan = plan_collapse(ws, u, v, CollapseGoal::quality)) {
      touched.mark(corners_of(ws.mesh, plan->star_u));
      apply_collapse(ws, *plan);
      return true;
    }
  }
  return false;
}

// With more than one thread, candidates are decided in batches, in
// parallel, on the mesh as the batch found it, then applied in order; a
// decision an operation applied before it in its batch may have changed is
// taken again in turn (each pass says when). The result is the one deciding
// them one by one gives: outputs are the same for any thread count.
//
// Runs plan_ahead(i) for the items of each batch in parallel, then
// apply(i, ahead) in order, `ahead` pointing to what plan_ahead(i) gave
// (null on one thread, where nothing is planned ahead). `touched` holds
// the vertices the batch's operations changed; it is cleared after each.
template <class Ahead, class PlanAhead, class Apply>
void in_planned_batches(std::size_t count, std::size_t batch, TouchedVertices& touched, PlanAhead plan_ahead,
                        Apply apply) {
  const bool parallel = tbb::this_task_arena::max_concurrency() > 1;
  std::vector<Ahead> planned;
  for (std::size_t first = 0; first < count; first += batch) {
    const std::size_t last = std::min(count, first + batch);
    planned.assign(last - first, Ahead{});
    if (parallel)
      tbb::parallel_for(tbb::blocked_range<std::size_t>(first, last, 4),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                            planned[i - first] = plan_ahead(i);
                        });
    for (std::size_t i = first; i < last; ++i) apply(i, parallel ? &planned[i - first] : nullptr);
    touched.clear();
  }
}

// A collapse changes only the tets around its removed vertex, so a decision
// stands unless a collapse applied before it had either end as a corner.
// Small batches: with 1,024 half of the accepted collapses were decided
// twice (trimesh/teapot).
constexpr std::size_t kCollapseBatch = 48;

// A split plan reads the tets around its edge, which a split applied
// before it changed only if it marked both ends; such plans, and those
// whose collected tet no longer has the edge, are made again.
constexpr std::size_t kSplitBatch = 64;

std::size_t split_pass(Workspace& ws) {
  const Mesh& mesh = ws.mesh;
  const auto long_edge = [](double length, double target) { return length > 4.0 / 3.0 * target; };
  const std::vector<EdgeCandidate> candidates = edge_candidates(ws, long_edge, true);
  const auto middle = [&](const EdgeCandidate& e) {
    return HybridPoint(Vec3d(0.5 * (mesh.position(e.a).approx + mesh.position(e.b).approx)));
  };
  // Whether the collected tet still has the edge: a read-only plan starts there.
  const auto has_edge = [&](const EdgeCandidate& e) {
    return mesh.tet_alive(e.tet) && mesh.corner_of(e.tet, e.a) >= 0 && mesh.corner_of(e.tet, e.b) >= 0;
  };
  TouchedVertices touched(mesh.vertex_slots());
  std::size_t done = 0;
  const auto plan_ahead = [&](std::size_t i) -> std::optional<SplitPlan> {
    const EdgeCandidate& e = candidates[i];
    if (!has_edge(e)) return std::nullopt;
    return plan_split(ws, e.a, e.b, middle(e), true, tets_around_edge(mesh, e.a, e.b, e.tet));
  };
  const auto apply = [&](std::size_t i, std::optional<SplitPlan>* ahead) {
    const EdgeCandidate& e = candidates[i];
    std::optional<SplitPlan> plan;
    // A tet with both ends that a split made or removed marked both.
    if (ahead != nullptr && has_edge(e) && !(touched[e.a] && touched[e.b])) {
      plan = std::move(*ahead);
    } else {
      std::vector<Index> around = ws.edge_tets(e.a, e.b, e.tet);
      if (around.empty()) return;
      plan = plan_split(ws, e.a, e.b, middle(e), true, std::move(around));
    }
    if (!plan) return;
    for (const Index t : plan->old_tets) touched.mark(mesh.tet(t));
    apply_split(ws, std::move(*plan));
    ++done;
  };
  in_planned_batches<std::optional<SplitPlan>>(candidates.size(), kSplitBatch, touched, plan_ahead, apply);
  return done;
}

std::size_t collapse_pass(Workspace& ws) {
  const double below = ws.collapse_below;
  const auto short_edge = [below](double length, double target) { return length < below * target; };
  const std::vector<EdgeCandidate> candidates = edge_candidates(ws, short_edge, false);
  const auto still_short = [&](const EdgeCandidate& e) {
    // The edge may have grown since the candidates were collected.
    return ws.mesh.vertex_alive(e.a) && ws.mesh.vertex_alive(e.b) &&
           edge_length(ws.mesh, e.a, e.b) < below * ws.target(e.a, e.b);
  };
  TouchedVertices touched(ws.mesh.vertex_slots());
  std::size_t done = 0;
  const auto plan_ahead = [&](std::size_t i) {
    const EdgeCandidate& e = candidates[i];
    return still_short(e) ? decide_edge_collapse(ws, e.a, e.b)
                          : EdgeCollapse{EdgeCollapse::Kind::undecided, {}};
  };
  const auto apply = [&](std::size_t i, const EdgeCollapse* ahead) {
    const EdgeCandidate& e = candidates[i];
    if (!still_short(e)) return;
    if (ahead == nullptr || ahead->kind == EdgeCollapse::Kind::undecided || touched[e.a] || touched[e.b]) {
      done += collapse_either_way(ws, e.a, e.b, touched) ? 1 : 0;
    } else if (ahead->kind == EdgeCollapse::Kind::planned) {
      touched.mark(corners_of(ws.mesh, ahead->plan.star_u));
      apply_collapse(ws, ahead->plan);
      ++done;
    }
  };
  in_planned_batches<EdgeCollapse>(candidates.size(), kCollapseBatch, touched, plan_ahead, apply);
  return done;
}

namespace {

void count_swap(int kind, SwapCounts& counts) {
  counts.s23 += kind == 2;
  counts.s32 += kind == 3;
  counts.s44 += kind == 4;
  counts.removals += kind > 4;
}

}  // namespace

// A swap plan for tet t read the tets around its edges and across its
// faces, each with two of t's corners or more; a swap applied before it
// changes only tets whose corners it marks, so the plan stands unless two
// of t's corners are marked.
constexpr std::size_t kSwapBatch = 64;

SwapCounts swap_pass(Workspace& ws) {
  constexpr double kWorthSwapping = 4.0;  // a regular tet has 3
  const Mesh& mesh = ws.mesh;
  const std::vector<double> energy = tet_energies(ws);
  std::vector<std::pair<double, Index>> bad;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t) && energy[t] > kWorthSwapping && touches_focus(ws, mesh.tet(t)))
      bad.emplace_back(-energy[t], t);
  }
  std::sort(bad.begin(), bad.end());
  std::vector<Tet> corners;
  for (const auto& [minus_energy, t] : bad) corners.push_back(mesh.tet(t));
  // Slots are reused: the tet must still be the one collected.
  const auto unchanged = [&](std::size_t i) {
    const Index t = bad[i].second;
    return mesh.tet_alive(t) && mesh.tet(t) == corners[i];
  };

  TouchedVertices touched(mesh.vertex_slots());
  SwapCounts counts;
  const auto plan_ahead = [&](std::size_t i) {
    return unchanged(i) ? plan_tet_swap(ws, bad[i].second) : std::nullopt;
  };
  const auto apply = [&](std::size_t i, std::optional<SwapPlan>* ahead) {
    if (!unchanged(i)) return;
    const Tet& c = corners[i];
    const auto marked = std::count_if(c.begin(), c.end(), [&](Index v) { return touched[v]; });
    const std::optional<SwapPlan> plan =
        ahead != nullptr && marked < 2 ? std::move(*ahead) : plan_tet_swap(ws, bad[i].second);
    if (!plan) return;
    for (const Index t : plan->old_tets) touched.mark(mesh.tet(t));
    apply_swap(ws, *plan);
    count_swap(plan->kind, counts);
  };
  in_planned_batches<std::optional<SwapPlan>>(bad.size(), kSwapBatch, touched, plan_ahead, apply);
  return counts;
}

std::size_t smooth_pass(Workspace& ws, bool soft_max) {
  const VertexTets incidence(ws.mesh);
  std::vector<char> moved(ws.mesh.vertex_slots(), 0);
  for (const std::vector<Index>& vertices : colour_classes(ws, incidence)) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const Index v = vertices[i];
                          moved[v] = try_smooth(ws, v, incidence.of(v), soft_max) ? 1 : 0;
                        }
                      });
  }
  return std::size_t(std::count(moved.begin(), moved.end(), 1));
}

}  // namespace mr::tetmesh::improve_detail
