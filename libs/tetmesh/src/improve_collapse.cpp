// Edge collapse: vertex u is removed and its tets are re-attached to v. The
// tets around the edge (u, v) disappear and their two faces away from the
// edge merge (the merged face keeps the ids of both).

#include "improve_local.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mr::tetmesh::improve_detail {
namespace {

using Edge = std::array<Index, 2>;

// The link of a vertex: vertices, edges and triangles of the faces opposite it.
struct Link {
  std::vector<Index> vertices;
  std::vector<Edge> edges;
  std::vector<FaceKey> triangles;

  void finish() {
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::sort(triangles.begin(), triangles.end());
  }
};

Link vertex_link(const Mesh& mesh, std::span<const Index> star, Index v) {
  Link link;
  for (const Index t : star) {
    const FaceKey face = face_key(mesh.face_vertices(t, mesh.corner_of(t, v)));
    link.vertices.insert(link.vertices.end(), face.begin(), face.end());
    link.edges.push_back({face[0], face[1]});
    link.edges.push_back({face[0], face[2]});
    link.edges.push_back({face[1], face[2]});
    link.triangles.push_back(face);
  }
  link.finish();
  return link;
}

// The link of edge (u, v): the edges opposite it in its tets, and their vertices.
Link edge_link(const Mesh& mesh, std::span<const Index> edge_tets, Index u, Index v) {
  Link link;
  for (const Index t : edge_tets) {
    Edge opposite{};
    int k = 0;
    for (const Index w : mesh.tet(t)) {
      if (w != u && w != v) opposite[k++] = w;
    }
    std::sort(opposite.begin(), opposite.end());
    link.vertices.insert(link.vertices.end(), opposite.begin(), opposite.end());
    link.edges.push_back(opposite);
  }
  link.finish();
  return link;
}

template <class T>
std::vector<T> intersection(const std::vector<T>& a, const std::vector<T>& b) {
  std::vector<T> out;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// lk(u) ∩ lk(v) == lk(uv): the collapse keeps the tet mesh a manifold.
bool tet_link_condition(const Link& lu, const Link& lv, const Link& luv) {
  return intersection(lu.vertices, lv.vertices) == luv.vertices &&
         intersection(lu.edges, lv.edges) == luv.edges && intersection(lu.triangles, lv.triangles).empty();
}

// Surface neighbours of v (other corners of its tracked faces), sorted.
std::vector<Index> surface_neighbours(const std::vector<TrackedFace>& faces, Index v) {
  std::vector<Index> out;
  for (const TrackedFace& f : faces) {
    for (const Index w : f.key) {
      if (w != v) out.push_back(w);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool contains(const FaceKey& key, Index v) { return std::find(key.begin(), key.end(), v) != key.end(); }

// Number of faces among `faces` that contain both a and b.
std::size_t faces_on_edge(const std::vector<TrackedFace>& faces, Index a, Index b) {
  return std::size_t(std::count_if(faces.begin(), faces.end(), [&](const TrackedFace& f) {
    return contains(f.key, a) && contains(f.key, b);
  }));
}

// The surface neighbours x of u whose edge (u, x) does not have exactly two
// faces: an open boundary (one face) or a line where surfaces meet or cross
// (three or more). Such edges form the surface's feature lines.
std::vector<Index> feature_neighbours(const std::vector<TrackedFace>& at_u, Index u) {
  std::vector<Index> out;
  for (const Index x : surface_neighbours(at_u, u)) {
    if (faces_on_edge(at_u, u, x) != 2) out.push_back(x);
  }
  return out;
}

// Whether collapsing u onto v keeps the tracked surface's topology:
// - uv is a surface edge, and the link condition of the surface (a
//   2-complex) holds: the common neighbours of u and v are exactly the third
//   corners of the faces on uv, and no two faces (u, a, b), (v, a, b) exist;
// - feature lines are kept: a vertex on one (not at a corner where lines
//   meet or end) may only slide along it, so u must have exactly two
//   feature edges of the same multiplicity, uv being one of them. Vertices
//   off every feature line may collapse along any manifold edge.
bool surface_allows(const std::vector<TrackedFace>& at_u, const std::vector<TrackedFace>& at_v, Index u,
                    Index v) {
  const std::size_t on_uv = faces_on_edge(at_u, u, v);
  if (on_uv == 0) return false;
  const std::vector<Index> features = feature_neighbours(at_u, u);
  if (!features.empty()) {
    if (features.size() != 2 || !std::binary_search(features.begin(), features.end(), v)) return false;
    const Index w = features[0] == v ? features[1] : features[0];
    if (faces_on_edge(at_u, u, w) != on_uv) return false;
  }
  std::vector<Index> across;  // third corners of the faces on edge uv
  for (const TrackedFace& f : at_u) {
    if (!contains(f.key, v)) continue;
    for (const Index w : f.key) {
      if (w != u && w != v) across.push_back(w);
    }
  }
  std::sort(across.begin(), across.end());
  if (intersection(surface_neighbours(at_u, u), surface_neighbours(at_v, v)) != across) return false;
  // Faces (u, a, b) and (v, a, b) would become one face twice.
  for (const TrackedFace& f : at_u) {
    if (contains(f.key, v)) continue;
    FaceKey moved = f.key;
    std::replace(moved.begin(), moved.end(), u, v);
    moved = face_key(moved);
    if (std::any_of(at_v.begin(), at_v.end(), [&](const TrackedFace& g) { return g.key == moved; })) {
      return false;
    }
  }
  return true;
}

// The tracked faces at v (in its star) where the carried decision changes:
// the faces the written mesh's boundary will be made of.
std::vector<TrackedFace> deciding_faces_at(const Workspace& ws, std::span<const Index> star, Index v) {
  const Mesh& mesh = ws.mesh;
  std::vector<TrackedFace> faces;
  for (const Index t : star) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.tet(t)[f] == v || !mesh.is_surface_face(t, f)) continue;
      if (ws.kept_side(t) == ws.kept_side(mesh.neighbour(t, f))) continue;
      faces.push_back({face_key(mesh.face_vertices(t, f)), {}});
    }
  }
  std::sort(faces.begin(), faces.end(),
            [](const TrackedFace& a, const TrackedFace& b) { return a.key < b.key; });
  faces.erase(std::unique(faces.begin(), faces.end(),
                          [](const TrackedFace& a, const TrackedFace& b) { return a.key == b.key; }),
              faces.end());
  return faces;
}

// The tracked faces at a vertex, and those among them whose topology a
// collapse must keep. Where the filter's decision is carried
// (TetPayload::value), those are the faces where it changes, of which the
// written mesh's boundary is made: the other tracked faces (copies that
// overlap, parts that graze, inner pieces of crossing parts) only stay in
// the envelope, so a vertex on them alone may pinch them onto another
// sheet, where a tet between vanishes merging its two faces. Nearly
// coincident sheets otherwise keep flat tets between them that no
// operation removes. Elsewhere, every tracked face binds.
struct SurfaceAt {
  std::vector<TrackedFace> tracked;
  std::vector<TrackedFace> binding;
  /// On tracked faces that bind nothing.
  bool free_sheet() const { return !tracked.empty() && binding.empty(); }
};

std::vector<TrackedFace> binding_faces_at(const Workspace& ws, bool carried, std::span<const Index> star,
                                          Index v) {
  return carried ? deciding_faces_at(ws, star, v) : tracked_faces_at(ws.mesh, star, v);
}

SurfaceAt surface_at(const Workspace& ws, bool carried, std::span<const Index> star, Index v) {
  SurfaceAt at{tracked_faces_at(ws.mesh, star, v), {}};
  if (!at.tracked.empty()) at.binding = carried ? deciding_faces_at(ws, star, v) : at.tracked;
  return at;
}

// How far a collapse that pinches a free sheet onto another (u on free
// faces, uv on none) may raise the energy of u's star (energy_raise).
// The flat tets between nearly coincident sheets go only once every vertex
// of one sheet is pinched onto the other, and the steps between are worse
// than the start: on the unit cube and a copy turned by 0.002 radians and
// moved by half of epsilon, max AMIPS 18.9 with a slack of 1, 9.3 with 4.
// Collapses along a free sheet keep the usual bound: with the slack there
// too, manifold/self_intersectA ended at 16.8 instead of 10.5.
constexpr double kPinchSlack = 4.0;

// Tracked edges with one face are open boundary: those u's collapse moves
// onto v must stay near the input's open boundary, not only near its surface.
bool open_edges_inside(const Workspace& ws, const std::vector<TrackedFace>& at_u, Index u, Index v) {
  if (ws.open_boundary == nullptr) return true;
  const Vec3d& pv = ws.mesh.position(v).approx;
  for (const Index x : surface_neighbours(at_u, u)) {
    if (x == v || faces_on_edge(at_u, u, x) != 1) continue;
    if (!ws.open_boundary->is_inside(pv, ws.mesh.position(x).approx)) return false;
  }
  return true;
}

// Whether the tracked faces at u, moved onto v, keep what they must: the
// binding ones their topology (surface_allows), all of them the envelope,
// and the open edges among them the envelope of the input's open edges.
bool surface_keeps(const Workspace& ws, bool carried, const SurfaceAt& at_u, std::span<const Index> star_v,
                   Index u, Index v) {
  if (at_u.tracked.empty()) return true;
  if (!at_u.binding.empty() && !surface_allows(at_u.binding, binding_faces_at(ws, carried, star_v, v), u, v))
    return false;
  std::vector<FaceCorners> moved_faces;
  for (const TrackedFace& f : at_u.tracked) {
    if (contains(f.key, v)) continue;
    FaceCorners corners = f.key;
    std::replace(corners.begin(), corners.end(), u, v);
    moved_faces.push_back(corners);
  }
  return faces_inside(ws, moved_faces) && open_edges_inside(ws, at_u.tracked, u, v);
}

// Collapses may raise the largest energy of a star up to this share of the
// stop energy. At the stop energy itself they left tets just below it that
// smoothing and rounding then pushed past it: thingi10k/908460 ended at 12.7.
constexpr double kCollapseCeiling = 0.8;

// How much a collapse for quality raises the largest energy of the tets
// that count: the new largest over max(theirs before, kCollapseCeiling
// times the stop energy), infinite when it leaves a tet flat on the doubles
// (infinite energy), counted or not. Up to 1 is allowed, up to kPinchSlack
// for a pinch.
double energy_raise(const Workspace& ws, std::span<const Index> star_u, std::span<const Tet> new_tets,
                    std::span<const std::size_t> origin) {
  double old_max = 0, new_max = 0;
  for (const Index t : star_u) {
    if (ws.counts(t)) old_max = std::max(old_max, tet_energy(ws.mesh, t));
  }
  for (std::size_t i = 0; i < new_tets.size(); ++i) {
    const double e = max_energy(ws.mesh, std::span<const Tet>(&new_tets[i], 1));
    if (!std::isfinite(e)) return std::numeric_limits<double>::infinity();
    if (ws.counts(star_u[origin[i]])) new_max = std::max(new_max, e);
  }
  return new_max / std::max(old_max, kCollapseCeiling * ws.stop_energy);
}

// The checks of a collapse of u onto v, on the mesh as it is: `star_u` is
// u's star, `star_of` gives another vertex's (asked only past the cheap
// checks). Changes nothing.
template <class StarOf>
std::optional<CollapsePlan> check_collapse(const Workspace& ws, Index u, Index v, std::vector<Index> star_u,
                                           StarOf&& star_of, CollapseGoal goal) {
  const Mesh& mesh = ws.mesh;
  if (u == v || !mesh.vertex_alive(u) || !mesh.vertex_alive(v)) return std::nullopt;
  if ((mesh.flags(u) & (kLocked | kOnBoundary | kOnBox)) != 0) return std::nullopt;
  std::vector<Index> uv_tets;
  for (const Index t : star_u) {
    if (mesh.corner_of(t, v) >= 0) uv_tets.push_back(t);
  }
  if (uv_tets.empty() || vertex_on_hull(mesh, star_u, u)) return std::nullopt;

  CollapsePlan plan{u, v, {}, {}, {}};
  for (std::size_t i = 0; i < star_u.size(); ++i) {
    if (mesh.corner_of(star_u[i], v) >= 0) continue;
    Tet moved = mesh.tet(star_u[i]);
    std::replace(moved.begin(), moved.end(), u, v);
    plan.new_tets.push_back(moved);
    plan.origin.push_back(i);
  }
  // Rounding only needs the exact test below: a new tet flat on the doubles
  // of its rational corners (a knot of cut points) becomes positive or is
  // checked again when they are rounded. Requiring finite energy here
  // refused nearly every collapse that would free a knot.
  const double raise =
      goal == CollapseGoal::quality ? energy_raise(ws, star_u, plan.new_tets, plan.origin) : 0.0;
  if (raise > kPinchSlack) return std::nullopt;

  const std::vector<Index> star_v = star_of(v);
  const Link lu = vertex_link(mesh, star_u, u);
  const Link lv = vertex_link(mesh, star_v, v);
  if (!tet_link_condition(lu, lv, edge_link(mesh, uv_tets, u, v))) return std::nullopt;
  if (!all_positive(mesh, plan.new_tets)) return std::nullopt;

  const bool carried = goal == CollapseGoal::quality && !ws.payload.value.empty();
  const SurfaceAt at_u = surface_at(ws, carried, star_u, u);
  const bool pinch = at_u.free_sheet() && faces_on_edge(at_u.tracked, u, v) == 0;
  if (raise > 1.0 && !pinch) return std::nullopt;
  if (!surface_keeps(ws, carried, at_u, star_v, u, v)) return std::nullopt;
  plan.star_u = std::move(star_u);
  return plan;
}

}  // namespace

void apply_collapse(Workspace& ws, const CollapsePlan& plan) {
  const auto parents = [u = plan.u, v = plan.v](const FaceKey& face, std::vector<FaceKey>& out) {
    out.push_back(face);
    if (!contains(face, v)) return;
    FaceKey before = face;
    std::replace(before.begin(), before.end(), v, u);
    out.push_back(face_key(before));
  };
  replace_tets(ws, plan.star_u, plan.new_tets, parents, plan.origin);
  ws.mesh.remove_vertex(plan.u);
}

std::optional<CollapsePlan> plan_collapse(Workspace& ws, Index u, Index v, CollapseGoal goal) {
  return check_collapse(
      ws, u, v, ws.star(u), [&ws](Index x) { return ws.star(x); }, goal);
}

bool try_collapse(Workspace& ws, Index u, Index v, CollapseGoal goal) {
  const std::optional<CollapsePlan> plan = plan_collapse(ws, u, v, goal);
  if (plan) apply_collapse(ws, *plan);
  return plan.has_value();
}

EdgeCollapse decide_edge_collapse(const Workspace& ws, Index a, Index b) {
  const std::optional<std::vector<Index>> star_a = ws.seeded_star(a), star_b = ws.seeded_star(b);
  if (!star_a || !star_b) return {EdgeCollapse::Kind::undecided, {}};
  const auto star_of = [&](Index x) { return x == a ? *star_a : *star_b; };
  std::optional<CollapsePlan> plan = check_collapse(ws, a, b, *star_a, star_of, CollapseGoal::quality);
  if (!plan) plan = check_collapse(ws, b, a, *star_b, star_of, CollapseGoal::quality);
  if (!plan) return {EdgeCollapse::Kind::refused, {}};
  return {EdgeCollapse::Kind::planned, std::move(*plan)};
}

}  // namespace mr::tetmesh::improve_detail
