#include "passes.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <queue>

namespace mr::simplify {
namespace {

constexpr std::size_t kBatchSize = 256;

struct Candidate {
  double cost = 0.0;
  std::uint32_t halfedge = 0;
  std::uint32_t stamp = 0;
  // Cheapest first; ties broken by halfedge index so the order is total.
  bool operator>(const Candidate& other) const {
    return cost != other.cost ? cost > other.cost : halfedge > other.halfedge;
  }
};

// Candidates cheapest first. Whether halfedges may leave a vertex at all
// (MeshState::may_collapse_from) takes the vertex's valence in time and is
// kept per vertex: a collapse changes the fans of v1 and of v0's neighbours
// only, and requeue_around pushes every halfedge leaving those again. Asked
// per halfedge instead, a vertex collapses gather thousands of faces on cost
// its valence squared at each change (half of simplifying
// manifold/Generic_Twin's input).
class CollapseQueue {
 public:
  explicit CollapseQueue(const MeshState& state)
      : state_(state),
        stamps_(state.mesh().n_halfedges(), 0),
        queued_cost_(state.mesh().n_halfedges(), kNotQueued),
        movable_(state.mesh().n_vertices(), 0) {}

  void fill_initially() {
    const TriMesh& mesh = state_.mesh();
    tbb::parallel_for(std::size_t(0), mesh.n_vertices(), [&](std::size_t i) {
      movable_[i] = state_.may_collapse_from(TriMesh::VertexHandle(static_cast<int>(i)));
    });
    const std::size_t n = mesh.n_halfedges();
    std::vector<double> costs(n, -1.0);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      const TriMesh::HalfedgeHandle h(static_cast<int>(i));
      if (is_candidate(h)) costs[i] = state_.collapse_cost(h);
    });
    std::vector<Candidate> all;
    for (std::size_t i = 0; i < n; ++i)
      if (costs[i] >= 0.0) all.push_back({costs[i], static_cast<std::uint32_t>(i), 0});
    queued_cost_ = std::move(costs);  // kNotQueued (-1) where not a candidate
    heap_ = Heap(std::greater<Candidate>(), std::move(all));
  }

  /// Queues h again; its from-vertex's fan must be unchanged since that
  /// vertex was last asked about (or was asked again through push_leaving).
  /// An entry still queued at the same cost stays: it pops where a new one
  /// would (the order is by cost, then halfedge), and the heap does not
  /// fill with stale copies (a collapse queues every halfedge leaving its
  /// one-ring again, and most keep their cost).
  void push(TriMesh::HalfedgeHandle h) {
    const auto i = static_cast<std::size_t>(h.idx());
    if (!is_candidate(h)) {
      ++stamps_[i];
      queued_cost_[i] = kNotQueued;
      return;
    }
    const double cost = state_.collapse_cost(h);
    if (queued_cost_[i] == cost) return;
    ++stamps_[i];
    queued_cost_[i] = cost;
    heap_.push({cost, std::uint32_t(i), stamps_[i]});
  }
  /// Queues every halfedge leaving v again, after v's fan changed.
  void push_leaving(TriMesh::VertexHandle v) {
    movable_[v.idx()] = state_.may_collapse_from(v);
    for (auto h : state_.mesh().voh_range(v)) push(h);
  }
  /// Puts back candidates popped (cheapest first) and not taken. They are
  /// cheaper than anything still waiting, so they go before it in a sorted
  /// list that pop() merges with the heap: the same order as pushing them
  /// back, without a heap operation each (batches of overlapping regions
  /// put back up to 1024 a batch: a sixth of simplifying
  /// manifold/Generic_Twin went into sifting them through the heap).
  void put_back(std::vector<Candidate>&& popped) {
    for (const Candidate& c : popped) queued_cost_[c.halfedge] = c.cost;
    popped.insert(popped.end(), waiting_.begin() + std::ptrdiff_t(next_waiting_), waiting_.end());
    waiting_ = std::move(popped);
    next_waiting_ = 0;
  }

  /// The cheapest current candidate, or false when none is left.
  bool pop(Candidate& out) {
    for (;;) {
      if (next_waiting_ < waiting_.size() && (heap_.empty() || heap_.top() > waiting_[next_waiting_])) {
        out = waiting_[next_waiting_++];
      } else if (!heap_.empty()) {
        out = heap_.top();
        heap_.pop();
      } else {
        return false;
      }
      if (out.stamp != stamps_[out.halfedge]) continue;  // stale
      queued_cost_[out.halfedge] = kNotQueued;
      if (is_candidate(TriMesh::HalfedgeHandle(int(out.halfedge)))) return true;
    }
  }

 private:
  using Heap = std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>>;
  bool is_candidate(TriMesh::HalfedgeHandle h) const {
    return state_.halfedge_may_collapse(h) && movable_[state_.mesh().from_vertex_handle(h).idx()] != 0;
  }

  const MeshState& state_;
  static constexpr double kNotQueued = -1.0;  ///< costs are never negative
  std::vector<std::uint32_t> stamps_;
  std::vector<double> queued_cost_;  ///< per halfedge: the cost of its live entry, or kNotQueued
  std::vector<char> movable_;        ///< per vertex: may_collapse_from when last asked
  Heap heap_;
  std::vector<Candidate> waiting_;  ///< put back, cheapest first, from next_waiting_ on
  std::size_t next_waiting_ = 0;
};

// Whether no vertex of v0's region (v0 and its one-ring) is marked with
// `batch_id`. Stops at the first marked one: a vertex that gathered
// thousands of faces is asked again and again while its neighbours are busy.
bool region_free(const TriMesh& mesh, TriMesh::VertexHandle v0, const std::vector<std::uint32_t>& marks,
                 std::uint32_t batch_id) {
  if (marks[v0.idx()] == batch_id) return false;
  for (auto v : mesh.vv_range(v0))
    if (marks[v.idx()] == batch_id) return false;
  return true;
}

// Pops up to kBatchSize candidates whose regions (v0 and its one-ring) are
// pairwise disjoint; the others are pushed back after the batch.
std::vector<Candidate> pop_batch(const TriMesh& mesh, CollapseQueue& queue, std::vector<std::uint32_t>& marks,
                                 std::uint32_t batch_id) {
  std::vector<Candidate> batch;
  std::vector<Candidate> deferred;
  Candidate c;
  while (batch.size() < kBatchSize && deferred.size() < 4 * kBatchSize && queue.pop(c)) {
    const TriMesh::HalfedgeHandle h(static_cast<int>(c.halfedge));
    const auto v0 = mesh.from_vertex_handle(h);
    if (!region_free(mesh, v0, marks, batch_id)) {
      deferred.push_back(c);
      continue;
    }
    marks[v0.idx()] = batch_id;
    for (auto v : mesh.vv_range(v0)) marks[v.idx()] = batch_id;
    batch.push_back(c);
  }
  queue.put_back(std::move(deferred));
  return batch;
}

// The box of v0 and its one-ring: where a collapse of v0 changes faces.
Eigen::AlignedBox3d collapse_region(const MeshState& state, TriMesh::HalfedgeHandle h) {
  const TriMesh& mesh = state.mesh();
  const auto v0 = mesh.from_vertex_handle(h);
  Eigen::AlignedBox3d box(state.point(v0));
  for (auto v : mesh.vv_range(v0)) box.extend(state.point(v));
  return box;
}

bool meets_any(const std::vector<Eigen::AlignedBox3d>& boxes, const Eigen::AlignedBox3d& box) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const auto& b) { return b.intersects(box); });
}

void requeue_around(const TriMesh& mesh, CollapseQueue& queue,
                    const std::vector<TriMesh::VertexHandle>& support, TriMesh::VertexHandle v1) {
  for (auto s : support) queue.push_leaving(s);
  for (auto h : mesh.vih_range(v1)) queue.push(h);
}

}  // namespace

std::size_t collapse_edges(MeshState& state, std::size_t target_faces) {
  TriMesh& mesh = state.mesh();
  CollapseQueue queue(state);
  queue.fill_initially();
  std::vector<std::uint32_t> marks(mesh.n_vertices(), 0);
  std::size_t collapses = 0;
  std::vector<TriMesh::VertexHandle> support;
  std::vector<Eigen::AlignedBox3d> changed;  // regions of the batch's collapses so far
  for (std::uint32_t batch_id = 1; state.face_count() > target_faces; ++batch_id) {
    const std::vector<Candidate> batch = pop_batch(mesh, queue, marks, batch_id);
    if (batch.empty()) break;
    state.bound_caches();
    // Every check on the surface before the batch, in parallel; the regions
    // are disjoint, so only whether new faces cross others can change, and
    // only near a collapse made before in the batch: asked again there.
    std::vector<std::uint8_t> local(batch.size(), 0), apart(batch.size(), 0);
    tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) {
      const TriMesh::HalfedgeHandle h(static_cast<int>(batch[i].halfedge));
      local[i] = state.collapse_passes_local_checks(h);
      apart[i] = local[i] && state.collapse_keeps_faces_apart(h);
    });
    changed.clear();
    for (std::size_t i = 0; i < batch.size() && state.face_count() > target_faces; ++i) {
      const TriMesh::HalfedgeHandle h(static_cast<int>(batch[i].halfedge));
      if (!local[i] || !mesh.is_collapse_ok(h)) continue;
      const Eigen::AlignedBox3d region = collapse_region(state, h);
      const bool keeps_apart =
          meets_any(changed, region) ? state.collapse_keeps_faces_apart(h) : apart[i] != 0;
      if (!keeps_apart || !state.collapse_keeps_volume(h)) continue;
      changed.push_back(region);
      const auto v0 = mesh.from_vertex_handle(h);
      const auto v1 = mesh.to_vertex_handle(h);
      support.clear();
      for (auto v : mesh.vv_range(v0))
        if (v != v1) support.push_back(v);
      support.push_back(v1);
      state.collapse(h);
      ++collapses;
      requeue_around(mesh, queue, support, v1);
    }
  }
  return collapses;
}

}  // namespace mr::simplify
