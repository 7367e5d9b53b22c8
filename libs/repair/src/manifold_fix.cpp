#include <mr/repair/manifold_fix.h>

#include "boundary_defects.h"
#include "collar.h"
#include "solid_edit.h"
#include "tet_set.h"
#include "vertex_split.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <optional>
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

std::size_t split_round(TetMesh& mesh, std::vector<TetState>& states, const FaceNeighbours& neighbours,
                        const std::vector<FaceRef>& boundary, const BoundaryDefects& defects,
                        double max_move) {
  const std::vector<Index> to_split = defect_vertices(defects);
  const VertexStars stars(mesh.tets, mesh.positions.size(), to_split);
  const spatial::BoxGrid grid = grid_of_boundary(mesh, boundary, max_move, stars, to_split);
  const SplitContext context{mesh, neighbours, states, boundary, max_move, grid};
  std::size_t copies = 0;
  for (Index v : to_split) copies += split_vertex(context, v, stars.of(v));
  return copies;
}

std::vector<Index> tets_around_edge(const VertexStars& stars, const std::array<Index, 2>& edge) {
  const auto a = stars.of(edge[0]), b = stars.of(edge[1]);
  std::vector<Index> both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
  return both;
}

// The tets of `region` in the solid, and those the fix may add, each split
// into face-connected classes.
std::vector<std::vector<Index>> edit_candidates(const FaceNeighbours& neighbours,
                                                std::span<const TetState> states,
                                                const std::vector<Index>& region,
                                                bool whole_solid_if_connected) {
  std::vector<Index> solid, rejected;
  for (Index t : region) {
    if (in_solid(states[t]))
      solid.push_back(t);
    else if (states[t] == TetState::rejected)
      rejected.push_back(t);
  }
  auto candidates = face_connected_classes(neighbours, solid);
  if (whole_solid_if_connected && candidates.size() == 1) candidates.front() = solid;
  for (auto& c : face_connected_classes(neighbours, rejected)) candidates.push_back(std::move(c));
  return candidates;
}

// Edits the solid once for each defect whose tets are all unchanged this
// round: removes the best fan of solid tets around a non-manifold edge, or
// one class of them around a non-manifold vertex (all of them when they
// are connected), or adds a fan of rejected tets there instead.
class EditRound {
 public:
  EditRound(const TetMesh& mesh, std::vector<TetState>& states, const FaceNeighbours& neighbours,
            const BoundaryDefects& defects, const envelope::Envelope* envelope, ManifoldFixStats& stats)
      : mesh_(mesh),
        states_(states),
        neighbours_(neighbours),
        envelope_(envelope),
        stats_(stats),
        defects_(defects),
        stars_(mesh.tets, mesh.positions.size(), defect_vertices(defects)),
        changed_(mesh.tets.size(), 0),
        solid_tets_(std::count_if(states.begin(), states.end(), in_solid)) {}

  /// Edits at the defects it was made for.
  std::size_t run() {
    std::size_t edits = 0;
    for (const auto& edge : defects_.nonmanifold_edges) {
      const std::vector<Index> around = tets_around_edge(stars_, edge);
      edits += edit_one_of(edit_candidates(neighbours_, states_, around, false), around);
    }
    for (Index v : defects_.nonmanifold_vertices) {
      const std::vector<Index> star(stars_.of(v).begin(), stars_.of(v).end());
      edits += edit_one_of(edit_candidates(neighbours_, states_, star, true), star);
    }
    return edits;
  }

 private:
  std::size_t edit_one_of(const std::vector<std::vector<Index>>& candidates,
                          const std::vector<Index>& region) {
    if (std::any_of(region.begin(), region.end(), [&](Index t) { return changed_[t] != 0; })) return 0;
    const auto edit = choose_edit(mesh_, neighbours_, states_, solid_tets_, candidates, envelope_);
    if (!edit) return 0;
    for (Index t : edit->tets) {
      states_[t] = edit->add ? TetState::solid : TetState::locked_out;
      changed_[t] = 1;
    }
    if (edit->add) {
      solid_tets_ += edit->tets.size();
      stats_.added_tets += edit->tets.size();
    } else {
      solid_tets_ -= edit->tets.size();
      stats_.removed_tets += edit->tets.size();
    }
    stats_.faces_outside_envelope += edit->faces_outside;
    return 1;
  }

  const TetMesh& mesh_;
  std::vector<TetState>& states_;
  const FaceNeighbours& neighbours_;
  const envelope::Envelope* envelope_;
  ManifoldFixStats& stats_;
  const BoundaryDefects& defects_;
  VertexStars stars_;
  std::vector<std::uint8_t> changed_;
  std::size_t solid_tets_;
};

std::vector<TetState> initial_states(std::span<const std::uint8_t> inside, std::size_t tets) {
  if (!inside.empty() && inside.size() != tets)
    throw UsageError("manifold fix: " + std::to_string(inside.size()) + " inside flags for " +
                     std::to_string(tets) + " tets");
  std::vector<TetState> states(tets, TetState::solid);
  for (std::size_t t = 0; t < inside.size(); ++t)
    if (inside[t] == 0) states[t] = TetState::rejected;
  return states;
}

// Leaves in `mesh` the solid's tets and the vertices they use.
void keep_solid_only(TetMesh& mesh, std::span<const TetState> states) {
  constexpr Index kUnused = Index(-1);
  std::vector<Index> new_index(mesh.positions.size(), kUnused);
  std::vector<Vec3d> positions;
  std::size_t tets = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (!in_solid(states[t])) continue;
    Tet tet = mesh.tets[t];
    for (Index& v : tet) {
      if (new_index[v] == kUnused) {
        new_index[v] = static_cast<Index>(positions.size());
        positions.push_back(mesh.positions[v]);
      }
      v = new_index[v];
    }
    mesh.tets[tets++] = tet;
  }
  mesh.tets.resize(tets);
  mesh.positions = std::move(positions);
}

// The solid's boundary and its defects, for the tets as they are now.
struct Examined {
  FaceNeighbours neighbours;
  std::vector<FaceRef> boundary;
  BoundaryDefects defects;
};

// `neighbours` from an earlier round when the tets are the same ones:
// splits and edits leave face neighbours valid (tet_set.h), and building
// them anew was most of the fix's time on large meshes (trimesh/soup: 2M
// tets, 23 rounds).
Examined examine(const TetMesh& mesh, std::span<const TetState> states, FaceNeighbours neighbours) {
  std::vector<FaceRef> boundary = boundary_faces(neighbours, states);
  BoundaryDefects defects = find_boundary_defects(triangles_of(mesh, boundary));
  return {std::move(neighbours), std::move(boundary), std::move(defects)};
}

Examined examine(const TetMesh& mesh, std::span<const TetState> states) {
  return examine(mesh, states, FaceNeighbours(mesh.tets));
}

// The fallback (manifold_fix.h): while defects remain, every tet around a
// defect vertex joins the solid. Terminates: each step adds a tet.
void fill_defect_stars(const TetMesh& mesh, std::vector<TetState>& states, ManifoldFixStats& stats) {
  const VertexStars stars(mesh.tets, mesh.positions.size());
  for (;;) {
    const Examined now = examine(mesh, states);
    if (now.defects.manifold()) return;
    ++stats.fallback_steps;
    std::size_t added = 0;
    for (Index v : defect_vertices(now.defects))
      for (Index t : stars.of(v))
        if (!in_solid(states[t])) {
          states[t] = TetState::solid;
          ++added;
        }
    if (added == 0)
      throw RunError("repair: internal error: a defect vertex has every tet around it in the solid");
    stats.fallback_added_tets += added;
  }
}

}  // namespace

ManifoldFixStats make_boundary_manifold(TetMesh& mesh, std::span<const std::uint8_t> inside,
                                        const envelope::Envelope* envelope,
                                        const ManifoldFixOptions& options) {
  if (!(options.max_move > 0.0) || !std::isfinite(options.max_move))
    throw UsageError("manifold fix: the largest vertex move must be finite and > 0");
  if (options.max_rounds < 1) throw UsageError("manifold fix: at least one round is needed");
  mesh.tet_labels.clear();
  mesh.faces.clear();
  mesh.face_labels.clear();
  std::vector<TetState> states = initial_states(inside, mesh.tets.size());
  const TetMesh unchanged = mesh;  // for the fallback
  ManifoldFixStats stats;
  std::optional<FaceNeighbours> kept;  // of the previous round, if no tet came since
  for (int round = 0;; ++round) {
    Examined now = kept ? examine(mesh, states, std::move(*kept)) : examine(mesh, states);
    kept.reset();
    if (round == 0) {
      stats.nonmanifold_edges_found = now.defects.nonmanifold_edges.size();
      stats.nonmanifold_vertices_found = now.defects.nonmanifold_vertices.size();
    }
    // Collars (collar.h) at every defect vertex, in each of the first
    // rounds: again at vertices that had one, because splits refused in one
    // round (a part not positive) may go through after the vertex moves of
    // the next, and collar points that become defects need their own
    // (openscad-nonmanifold-crash: 3.07 eps with one collar per vertex of
    // the mesh, 0.81 with collars every round). Only in the first rounds,
    // to bound the work: collars every round kept chasing the defects edits
    // leave at collar points (trimesh/soup ran out of rounds).
    if (options.collar_width > 0.0 && round < options.collar_rounds && !now.defects.manifold()) {
      const std::size_t splits =
          build_collars(mesh, states, defect_vertices(now.defects), options.collar_width);
      stats.collar_splits += splits;
      if (splits > 0) now = examine(mesh, states);  // the same defects, on more tets
    }
    const FaceNeighbours& neighbours = now.neighbours;
    const std::vector<FaceRef>& boundary = now.boundary;
    const BoundaryDefects& defects = now.defects;
    if (defects.manifold()) {
      stats.rounds = round;
      keep_solid_only(mesh, states);
      return stats;
    }
    bool stuck = round == options.max_rounds;
    if (!stuck) {
      const std::size_t copies = split_round(mesh, states, neighbours, boundary, defects, options.max_move);
      stats.vertex_copies += copies;
      if (copies == 0) stuck = EditRound(mesh, states, neighbours, defects, envelope, stats).run() == 0;
      if (!stuck) {
        kept = std::move(now.neighbours);
        continue;
      }
    }
    if (stuck) {
      stats.rounds = round;
      stats.fell_back = true;
      mesh = unchanged;
      states = initial_states(inside, mesh.tets.size());
      fill_defect_stars(mesh, states, stats);
      keep_solid_only(mesh, states);
      return stats;
    }
  }
}

}  // namespace mr::repair
