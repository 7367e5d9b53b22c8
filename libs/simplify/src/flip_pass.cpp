#include "passes.h"

#include <tbb/parallel_for.h>

namespace mr::simplify {
namespace {

// One sweep: every edge is judged on the mesh as it was at the start of the
// sweep; an edge whose faces another flip of this sweep already changed waits
// for the next sweep.
std::size_t flip_sweep(MeshState& state) {
  TriMesh& mesh = state.mesh();
  const std::size_t n = mesh.n_edges();
  state.bound_caches();
  std::vector<std::uint8_t> improves(n, 0);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    improves[i] = state.flip_improves_locally(TriMesh::EdgeHandle(static_cast<int>(i)));
  });
  std::vector<std::uint8_t> face_changed(mesh.n_faces(), 0);
  std::size_t flips = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!improves[i]) continue;
    const TriMesh::EdgeHandle e(static_cast<int>(i));
    const auto f0 = mesh.face_handle(mesh.halfedge_handle(e, 0));
    const auto f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
    if (face_changed[f0.idx()] || face_changed[f1.idx()]) continue;
    if (!mesh.is_flip_ok(e) || !state.flip_keeps_faces_apart(e) || !state.flip_keeps_volume(e)) continue;
    state.flip(e);
    face_changed[f0.idx()] = face_changed[f1.idx()] = 1;
    ++flips;
  }
  return flips;
}

}  // namespace

std::size_t flip_edges(MeshState& state, int passes) {
  std::size_t flips = 0;
  for (int pass = 0; pass < passes; ++pass) {
    const std::size_t flipped = flip_sweep(state);
    flips += flipped;
    if (flipped == 0) break;
  }
  return flips;
}

}  // namespace mr::simplify
