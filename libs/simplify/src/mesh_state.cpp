#include "mesh_state.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::simplify {

MeshState::MeshState(const TriangleSoup& input, const TriangleSoup& welded,
                     const DerivedTolerances& tolerances, std::span<const std::uint8_t> frozen_faces,
                     std::span<const std::array<Index, 2>> frozen_merges)
    : tolerances_(tolerances) {
  build_mesh(welded);
  lock_vertices(welded, frozen_faces, frozen_merges);
  envelope::EnvelopeOptions envelope_options;
  envelope_options.epsilon = tolerances_.epsilon;
  envelope_ = envelope::make_envelope(input, envelope_options);
  envelope_options.stage = 2;
  fine_envelope_ = envelope::make_envelope(input, envelope_options);
  build_boundary_envelope();
  build_grid();
  build_quadrics();
  build_component_volumes();
  carried_by_.resize(mesh_.n_faces());
}

// The halfedge mesh of the faces OpenMesh can hold; the others are kept aside.
// Copies of one triangle (the same three vertices, either orientation: a
// double-sided sheet, a face written twice) become one face that remembers
// how often each orientation occurs, so a soup of double-sided faces still
// has a manifold part to simplify. A face the halfedge structure refuses in
// its own orientation is tried reversed (orientation is restored on output).
// add_face is only called with faces can_add_face accepts: OpenMesh logs
// every face it refuses to std::cerr.
void MeshState::build_mesh(const TriangleSoup& welded) {
  const std::size_t n = welded.triangles.size();
  mesh_.reserve(welded.positions.size(), 3 * n / 2, n);
  for (const Vec3d& p : welded.positions) mesh_.add_vertex(TriMesh::Point(p.x(), p.y(), p.z()));
  mesh_.request_vertex_status();
  mesh_.request_edge_status();
  mesh_.request_halfedge_status();
  mesh_.request_face_status();

  // Group copies: sort by the sorted vertex triple, ties by input order, so
  // each group starts with its first occurrence.
  std::vector<std::pair<Triangle, std::size_t>> keys;
  keys.reserve(n);
  for (std::size_t f = 0; f < n; ++f) {
    Triangle key = welded.triangles[f];
    std::sort(key.begin(), key.end());
    keys.emplace_back(key, f);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::size_t> first(n);  // per input face: the first face of its group
  for (std::size_t k = 0; k < n; ++k)
    first[keys[k].second] =
        k > 0 && keys[k].first == keys[k - 1].first ? first[keys[k - 1].second] : keys[k].second;
  auto same_orientation = [](const Triangle& a, const Triangle& b) {
    for (int r = 0; r < 3; ++r)
      if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
    return false;
  };

  constexpr std::size_t kNone = std::size_t(-1);
  std::vector<std::size_t> face_of(n, kNone);  // per group's first face: its mesh face, if any
  std::vector<std::uint8_t> reversed(n, 0);    // per group's first face: added reversed
  for (std::size_t f = 0; f < n; ++f) {
    const Triangle& t = welded.triangles[f];
    const std::size_t g = first[f];
    if (g != f) {  // a copy of an earlier face: counted with it, or kept aside with it
      if (face_of[g] == kNone) {
        kept_aside_triangles_.push_back(t);
        continue;
      }
      ++duplicate_faces_;
      Copies& c = copies_[face_of[g]];
      (same_orientation(t, welded.triangles[g]) != bool(reversed[g]) ? c.along : c.against) += 1;
      continue;
    }
    const TriMesh::VertexHandle a{static_cast<int>(t[0])}, b{static_cast<int>(t[1])},
        c{static_cast<int>(t[2])};
    TriMesh::FaceHandle added;
    if (can_add_face(mesh_, a, b, c)) {
      added = mesh_.add_face(a, b, c);
    } else if (can_add_face(mesh_, a, c, b)) {
      added = mesh_.add_face(a, c, b);
      reversed[f] = 1;
    }
    if (!added.is_valid()) {
      kept_aside_triangles_.push_back(t);
      continue;
    }
    face_of[f] = static_cast<std::size_t>(added.idx());
    copies_.push_back(reversed[f] ? Copies{0, 1, true} : Copies{1, 0, false});
  }
  for (const Copies& c : copies_) live_faces_ += c.count();
  for (const Triangle& t : kept_aside_triangles_)
    kept_aside_.push_back({welded.positions[t[0]], welded.positions[t[1]], welded.positions[t[2]]});
}

std::size_t MeshState::locked_vertices() const {
  return static_cast<std::size_t>(std::count(locked_.begin(), locked_.end(), std::uint8_t(1)));
}

Vec3d MeshState::point(TriMesh::VertexHandle v) const {
  const auto& p = mesh_.point(v);
  return {p[0], p[1], p[2]};
}

Corners MeshState::corners(TriMesh::FaceHandle f) const {
  Corners c;
  int k = 0;
  for (auto v : mesh_.fv_range(f)) c[k++] = point(v);
  return c;
}

// Vertices of kept-aside faces stay where they are so those faces stay
// attached; so do vertices whose faces do not form one fan, and those of
// frozen faces, but for the merges asked for vertices that only frozen
// faces lock.
void MeshState::lock_vertices(const TriangleSoup& welded, std::span<const std::uint8_t> frozen_faces,
                              std::span<const std::array<Index, 2>> frozen_merges) {
  locked_.assign(mesh_.n_vertices(), 0);
  for (const Triangle& t : kept_aside_triangles_)
    for (Index v : t) locked_[v] = 1;
  for (auto v : mesh_.vertices())
    if (!mesh_.is_manifold(v)) locked_[v.idx()] = 1;
  for (const std::array<Index, 2>& merge : frozen_merges)
    if (!locked_[merge[0]] && merge[0] != merge[1]) merges_.push_back(merge);
  std::sort(merges_.begin(), merges_.end());
  merges_.erase(std::unique(merges_.begin(), merges_.end()), merges_.end());
  for (std::size_t f = 0; f < frozen_faces.size(); ++f)
    if (frozen_faces[f])
      for (Index v : welded.triangles[f]) locked_[v] = 1;
}

bool MeshState::has_merges(TriMesh::VertexHandle v0) const {
  const auto v = static_cast<Index>(v0.idx());
  const auto it = std::lower_bound(merges_.begin(), merges_.end(), std::array<Index, 2>{v, 0});
  return it != merges_.end() && (*it)[0] == v;
}

bool MeshState::may_merge(TriMesh::VertexHandle v0, TriMesh::VertexHandle v1) const {
  return std::binary_search(merges_.begin(), merges_.end(),
                            std::array<Index, 2>{static_cast<Index>(v0.idx()), static_cast<Index>(v1.idx())});
}

// Boundary edges of the manifold part, as degenerate triangles (a, b, a): the
// envelope of the input's boundary curve.
void MeshState::build_boundary_envelope() {
  TriangleSoup curve;
  curve.positions.reserve(mesh_.n_vertices());
  for (auto v : mesh_.vertices()) curve.positions.push_back(point(v));
  for (auto h : mesh_.halfedges())
    if (mesh_.is_boundary(h)) {
      const auto a = static_cast<Index>(mesh_.from_vertex_handle(h).idx());
      const auto b = static_cast<Index>(mesh_.to_vertex_handle(h).idx());
      curve.triangles.push_back({a, b, a});
    }
  if (curve.triangles.empty()) return;
  envelope::EnvelopeOptions options;
  options.epsilon = tolerances_.epsilon;
  boundary_envelope_ = envelope::make_envelope(curve, options);
}

void MeshState::build_grid() {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d hi = -lo;
  for (auto v : mesh_.vertices()) {
    lo = lo.cwiseMin(point(v));
    hi = hi.cwiseMax(point(v));
  }
  for (const Corners& c : kept_aside_)
    for (const Vec3d& p : c) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!(lo.x() <= hi.x())) return;
  double total_length = 0.0;
  for (auto e : mesh_.edges()) total_length += mesh_.calc_edge_length(e);
  const double diagonal = (hi - lo).norm();
  const double mean_length = mesh_.n_edges() ? total_length / double(mesh_.n_edges()) : diagonal;
  const double cell = std::max({2.0 * mean_length, diagonal / 2000.0, 1e-300});
  grid_ = spatial::BoxGrid(lo - Vec3d::Constant(cell), cell);
  for (auto f : mesh_.faces()) insert_into_grid(f);
  for (std::size_t k = 0; k < kept_aside_.size(); ++k) {
    const Corners& c = kept_aside_[k];
    grid_.insert(static_cast<std::uint32_t>(mesh_.n_faces() + k), c[0].cwiseMin(c[1]).cwiseMin(c[2]),
                 c[0].cwiseMax(c[1]).cwiseMax(c[2]));
  }
}

void MeshState::insert_into_grid(TriMesh::FaceHandle f) {
  const Corners c = corners(f);
  grid_.insert(static_cast<std::uint32_t>(f.idx()), c[0].cwiseMin(c[1]).cwiseMin(c[2]),
               c[0].cwiseMax(c[1]).cwiseMax(c[2]));
}

// Garland-Heckbert: each vertex sums the planes of its faces (unweighted, so
// the error is a sum of squared distances).
void MeshState::build_quadrics() {
  quadrics_.assign(mesh_.n_vertices(), Quadric());
  for (auto f : mesh_.faces()) {
    const Corners c = corners(f);
    const Vec3d n = (c[1] - c[0]).cross(c[2] - c[0]);
    const double length = n.norm();
    if (!(length > 0.0)) continue;
    const Vec3d u = n / length;
    const Quadric q(u.x(), u.y(), u.z(), -u.dot(c[0]));
    for (auto v : mesh_.fv_range(f)) quadrics_[v.idx()] += q;
  }
}

// All faces around v occur equally often in the output, in the same
// orientations. A collapse rewrites only the faces around v0, so requiring
// this keeps every region of doubled (or flipped) faces covering what it
// covered: the lines between such regions stay where they are.
bool MeshState::same_copies_around(TriMesh::VertexHandle v) const {
  const Copies* first = nullptr;
  for (auto f : mesh_.vf_range(v)) {
    const Copies& c = copies_[f.idx()];
    if (!first)
      first = &c;
    else if (!(c == *first))
      return false;
  }
  return true;
}

bool MeshState::may_collapse_from(TriMesh::VertexHandle v0) const {
  return (!locked_[v0.idx()] || has_merges(v0)) && same_copies_around(v0);
}

bool MeshState::halfedge_may_collapse(TriMesh::HalfedgeHandle h) const {
  if (mesh_.status(mesh_.edge_handle(h)).deleted()) return false;
  const auto v0 = mesh_.from_vertex_handle(h);
  if (locked_[v0.idx()] && !may_merge(v0, mesh_.to_vertex_handle(h))) return false;
  return !mesh_.is_boundary(v0) || mesh_.is_boundary(mesh_.edge_handle(h));
}

double MeshState::collapse_cost(TriMesh::HalfedgeHandle h) const {
  const auto v0 = mesh_.from_vertex_handle(h);
  const auto v1 = mesh_.to_vertex_handle(h);
  Quadric q = quadrics_[v0.idx()];
  q += quadrics_[v1.idx()];
  const double error = std::max(0.0, q(mesh_.point(v1)));
  return error + tolerances_.length_weight * (point(v1) - point(v0)).squaredNorm();
}

void MeshState::collapse(TriMesh::HalfedgeHandle h) {
  const auto v0 = mesh_.from_vertex_handle(h);
  const auto v1 = mesh_.to_vertex_handle(h);
  volume6_[component_[v1.idx()]] += collapse_volume_change(h);
  const TriMesh::FaceHandle gone[2] = {mesh_.face_handle(h), mesh_.opposite_face_handle(h)};
  for (const TriMesh::FaceHandle f : gone) {
    if (!f.is_valid()) continue;
    live_faces_ -= copies_[f.idx()].count();
    grid_.erase(static_cast<std::uint32_t>(f.idx()));
  }
  quadrics_[v1.idx()] += quadrics_[v0.idx()];
  std::vector<TriMesh::FaceHandle> fan;
  for (auto f : mesh_.vf_range(v0)) fan.push_back(f);
  std::vector<std::uint32_t> moving = take_carried_points(fan);
  moving.push_back(static_cast<std::uint32_t>(carried_positions_.size()));
  carried_positions_.push_back(point(v0));
  mesh_.collapse(h);
  fan.clear();
  for (auto f : mesh_.vf_range(v1)) {
    insert_into_grid(f);
    fan.push_back(f);
  }
  carry_by_nearest(moving, fan);
}

void MeshState::flip(TriMesh::EdgeHandle e) {
  const std::vector<TriMesh::FaceHandle> pair{mesh_.face_handle(mesh_.halfedge_handle(e, 0)),
                                              mesh_.face_handle(mesh_.halfedge_handle(e, 1))};
  volume6_[component_[mesh_.from_vertex_handle(mesh_.halfedge_handle(e, 0)).idx()]] += flip_volume_change(e);
  const std::vector<std::uint32_t> moving = take_carried_points(pair);
  mesh_.flip(e);
  for (auto f : pair) insert_into_grid(f);
  carry_by_nearest(moving, pair);
}

TriangleSoup MeshState::to_output() const {
  TriangleSoup soup;
  constexpr Index kUnused = Index(-1);
  std::vector<Index> remap(mesh_.n_vertices(), kUnused);
  auto output_index = [&](int v) {
    if (remap[v] == kUnused) {
      remap[v] = static_cast<Index>(soup.positions.size());
      soup.positions.push_back(point(TriMesh::VertexHandle(v)));
    }
    return remap[v];
  };
  for (auto f : mesh_.faces()) {
    if (mesh_.status(f).deleted()) continue;
    Triangle t{};
    int k = 0;
    for (auto v : mesh_.fv_range(f)) t[k++] = output_index(v.idx());
    const Copies& c = copies_[f.idx()];
    const Triangle r{t[0], t[2], t[1]};
    soup.triangles.insert(soup.triangles.end(), c.against_first ? c.against : c.along,
                          c.against_first ? r : t);
    soup.triangles.insert(soup.triangles.end(), c.against_first ? c.along : c.against,
                          c.against_first ? t : r);
  }
  for (const Triangle& t : kept_aside_triangles_)
    soup.triangles.push_back({output_index(int(t[0])), output_index(int(t[1])), output_index(int(t[2]))});
  return soup;
}

}  // namespace mr::simplify
