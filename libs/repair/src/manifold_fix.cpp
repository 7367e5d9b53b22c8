#include <mr/repair/manifold_fix.h>

#include "boundary_defects.h"
#include "tet_removal.h"
#include "tet_set.h"
#include "vertex_split.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mr::repair {
namespace {

using namespace detail;

std::vector<Triangle> triangles_of(const TetMesh& mesh, const std::vector<FaceRef>& faces) {
  std::vector<Triangle> triangles;
  triangles.reserve(faces.size());
  for (const FaceRef& f : faces) triangles.push_back(tet_face(mesh.tets[f.tet], f.face));
  return triangles;
}

// Vertices of non-manifold vertices and edges, increasing, without repeats.
std::vector<Index> defect_vertices(const BoundaryDefects& defects) {
  std::vector<Index> vertices = defects.nonmanifold_vertices;
  for (const auto& e : defects.nonmanifold_edges) vertices.insert(vertices.end(), e.begin(), e.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

std::size_t split_round(TetMesh& mesh, const FaceNeighbours& neighbours, const std::vector<FaceRef>& boundary,
                        const BoundaryDefects& defects, double max_move) {
  const VertexStars stars(mesh.tets, mesh.positions.size());
  const spatial::BoxGrid grid = grid_of_boundary(mesh, boundary, max_move);
  const SplitContext context{mesh, neighbours, boundary, max_move, grid};
  std::size_t copies = 0;
  for (Index v : defect_vertices(defects)) copies += split_vertex(context, v, stars.of(v));
  return copies;
}

std::vector<Index> tets_around_edge(const VertexStars& stars, const std::array<Index, 2>& edge) {
  const auto a = stars.of(edge[0]), b = stars.of(edge[1]);
  std::vector<Index> both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
  return both;
}

// Removes, for each defect whose tets are all still there, the best
// candidate: one fan around a non-manifold edge; one class of the tets
// around a non-manifold vertex, or all of them when they are connected.
class RemovalRound {
 public:
  RemovalRound(TetMesh& mesh, const FaceNeighbours& neighbours, const envelope::Envelope* envelope,
               ManifoldFixStats& stats)
      : mesh_(mesh), neighbours_(neighbours), envelope_(envelope), stats_(stats),
        stars_(mesh.tets, mesh.positions.size()), removed_(mesh.tets.size(), 0), remaining_(mesh.tets.size()) {}

  std::size_t run(const BoundaryDefects& defects) {
    for (const auto& edge : defects.nonmanifold_edges) {
      const std::vector<Index> around = tets_around_edge(stars_, edge);
      remove_one_of(face_connected_classes(neighbours_, around), around);
    }
    for (Index v : defects.nonmanifold_vertices) {
      const std::vector<Index> star(stars_.of(v).begin(), stars_.of(v).end());
      auto classes = face_connected_classes(neighbours_, star);
      if (classes.size() == 1) classes.front() = star;
      remove_one_of(classes, star);
    }
    const std::size_t removed = mesh_.tets.size() - remaining_;
    std::size_t kept = 0;
    for (std::size_t t = 0; t < mesh_.tets.size(); ++t)
      if (!removed_[t]) mesh_.tets[kept++] = mesh_.tets[t];
    mesh_.tets.resize(kept);
    return removed;
  }

 private:
  void remove_one_of(const std::vector<std::vector<Index>>& candidates, const std::vector<Index>& region) {
    if (std::any_of(region.begin(), region.end(), [&](Index t) { return removed_[t] != 0; })) return;
    const auto choice = choose_removal(mesh_, neighbours_, removed_, remaining_, candidates, envelope_);
    if (!choice) return;
    for (Index t : choice->tets) removed_[t] = 1;
    remaining_ -= choice->tets.size();
    stats_.removed_tets += choice->tets.size();
    stats_.faces_outside_envelope += choice->faces_outside;
  }

  TetMesh& mesh_;
  const FaceNeighbours& neighbours_;
  const envelope::Envelope* envelope_;
  ManifoldFixStats& stats_;
  VertexStars stars_;
  std::vector<std::uint8_t> removed_;
  std::size_t remaining_;
};

std::string describe(const BoundaryDefects& defects) {
  return std::to_string(defects.nonmanifold_edges.size()) + " non-manifold edges and " +
         std::to_string(defects.nonmanifold_vertices.size()) + " non-manifold vertices remain";
}

}  // namespace

ManifoldFixStats make_boundary_manifold(TetMesh& mesh, const envelope::Envelope* envelope,
                                        const ManifoldFixOptions& options) {
  if (!(options.max_move > 0.0) || !std::isfinite(options.max_move))
    throw UsageError("manifold fix: the largest vertex move must be finite and > 0");
  if (options.max_rounds < 1) throw UsageError("manifold fix: at least one round is needed");
  mesh.tet_labels.clear();
  mesh.faces.clear();
  mesh.face_labels.clear();
  ManifoldFixStats stats;
  for (int round = 0;; ++round) {
    const FaceNeighbours neighbours(mesh.tets);
    const std::vector<FaceRef> boundary = boundary_faces(neighbours, mesh.tets.size());
    const BoundaryDefects defects = find_boundary_defects(triangles_of(mesh, boundary));
    if (round == 0) {
      stats.nonmanifold_edges_found = defects.nonmanifold_edges.size();
      stats.nonmanifold_vertices_found = defects.nonmanifold_vertices.size();
    }
    if (defects.manifold()) {
      stats.rounds = round;
      return stats;
    }
    if (round == options.max_rounds)
      throw RunError("repair: the boundary is still not manifold after " + std::to_string(round) +
                     " rounds: " + describe(defects));
    const std::size_t copies = split_round(mesh, neighbours, boundary, defects, options.max_move);
    stats.vertex_copies += copies;
    if (copies > 0) continue;
    if (RemovalRound(mesh, neighbours, envelope, stats).run(defects) == 0)
      throw RunError("repair: cannot make the boundary manifold without removing every tet: " + describe(defects));
  }
}

}  // namespace mr::repair
