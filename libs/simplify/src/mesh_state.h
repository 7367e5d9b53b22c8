#pragma once
// The working state of one simplification: the halfedge mesh of the manifold
// part (copies of one triangle merged into one face that remembers them), which vertices must not move, the
// envelopes of the original input and of its boundary curve, a grid of current faces (for the exact
// self-intersection test), per-vertex quadrics (for the collapse cost) and
// the vertices removed so far, each carried by the face nearest to it.
// Checks are const and may run on many threads at once; operations are not.

#include <mr/spatial/box_grid.h>

#include <mr/core/openmesh_convert.h>
#include <mr/envelope/envelope.h>
#include <mr/simplify/simplify.h>

#include <OpenMesh/Core/Geometry/QuadricT.hh>

#include <tbb/concurrent_unordered_map.h>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace mr::simplify {

using Quadric = OpenMesh::Geometry::QuadricT<double>;
using Corners = std::array<Vec3d, 3>;

/// Tolerances derived from the user's options.
struct DerivedTolerances {
  double epsilon = 0.0;
  double cos_max_normal_deviation = 0.5;
  double length_weight = 1e-2;  ///< weight of the squared edge length in the collapse cost
};

class MeshState {
 public:
  /// `welded` has bit-identical vertices merged; `input` is the original soup
  /// whose envelope bounds every changed triangle.
  /// Vertices of the faces flagged in `frozen_faces` (empty, or one flag per
  /// face of `welded`) never move: those faces come out as they went in,
  /// except that a vertex of `frozen_merges` (vertex, into) pairs of `welded`
  /// may collapse into `into` (SimplifyOptions::frozen_merges).
  MeshState(const TriangleSoup& input, const TriangleSoup& welded, const DerivedTolerances& tolerances,
            std::span<const std::uint8_t> frozen_faces = {},
            std::span<const std::array<Index, 2>> frozen_merges = {});

  TriMesh& mesh() { return mesh_; }
  Vec3d point(TriMesh::VertexHandle v) const;
  const TriMesh& mesh() const { return mesh_; }
  std::size_t kept_aside_faces() const { return kept_aside_.size(); }
  std::size_t duplicate_faces() const { return duplicate_faces_; }
  std::size_t locked_vertices() const;
  /// Output faces: the halfedge mesh's with their copies, and the kept-aside ones.
  std::size_t face_count() const { return live_faces_ + kept_aside_.size(); }

  /// Whether halfedge h (v0 -> v1) may ever be collapsed, and at what cost.
  bool is_collapse_candidate(TriMesh::HalfedgeHandle h) const {
    return halfedge_may_collapse(h) && may_collapse_from(mesh_.from_vertex_handle(h));
  }
  /// The part of is_collapse_candidate that depends on v0 alone (it takes
  /// v0's valence in time): asked once for all halfedges leaving v0.
  bool may_collapse_from(TriMesh::VertexHandle v0) const;
  /// The part of is_collapse_candidate that depends on the halfedge alone.
  bool halfedge_may_collapse(TriMesh::HalfedgeHandle h) const;
  double collapse_cost(TriMesh::HalfedgeHandle h) const;

  /// Everything about collapsing h except the self-intersection test: locks,
  /// boundary curve, link condition, degeneracy, normals and the envelope.
  bool collapse_passes_local_checks(TriMesh::HalfedgeHandle h) const;
  /// No face after the collapse meets another improperly (exact).
  bool collapse_keeps_faces_apart(TriMesh::HalfedgeHandle h) const;
  void collapse(TriMesh::HalfedgeHandle h);
  /// Between batches of checks (none running): drops the older generation of
  /// cached envelope verdicts when the newer one has grown past its bound.
  /// Only time depends on it: a verdict dropped is computed again.
  void bound_caches();

  /// The flip of edge e raises the smallest angle of its two faces and
  /// passes the local checks (as for collapses).
  bool flip_improves_locally(TriMesh::EdgeHandle e) const;
  bool flip_keeps_faces_apart(TriMesh::EdgeHandle e) const;
  void flip(TriMesh::EdgeHandle e);

  /// The collapse (flip) keeps the sign of the volume of its component when
  /// that component is closed. Every face may turn a little and the surface
  /// stay free of crossings while a part thinner than epsilon ends up inside
  /// out (a 4-face strut of negative volume): no per-face test sees that.
  /// Asked when the operation is made, after those before it.
  bool collapse_keeps_volume(TriMesh::HalfedgeHandle h) const;
  bool flip_keeps_volume(TriMesh::EdgeHandle e) const;

  /// Vertices removed by collapses, each still within epsilon of the surface.
  std::size_t carried_points() const { return carried_positions_.size(); }

  /// The manifold part followed by the kept-aside faces, unreferenced vertices dropped.
  TriangleSoup to_output() const;

 private:
  /// How often a face of the halfedge mesh occurs in the output: copies of
  /// one input triangle (the same three vertices) share one face, in either
  /// orientation.
  struct Copies {
    std::uint32_t along = 1;     ///< with the face's halfedge orientation
    std::uint32_t against = 0;   ///< reversed
    bool against_first = false;  ///< the input's first copy is reversed: written first
    std::size_t count() const { return std::size_t(along) + against; }
    bool operator==(const Copies& o) const { return along == o.along && against == o.against; }
  };

  struct NewFace {
    Corners corners;
    Vec3d old_normal;  // of the face it replaces (zero if none or degenerate)
  };

  Corners corners(TriMesh::FaceHandle f) const;
  void build_mesh(const TriangleSoup& welded);
  void lock_vertices(const TriangleSoup& welded, std::span<const std::uint8_t> frozen_faces,
                     std::span<const std::array<Index, 2>> frozen_merges);
  bool may_merge(TriMesh::VertexHandle v0, TriMesh::VertexHandle v1) const;
  bool has_merges(TriMesh::VertexHandle v0) const;
  bool same_copies_around(TriMesh::VertexHandle v) const;
  void build_boundary_envelope();
  void build_grid();
  void build_quadrics();
  void insert_into_grid(TriMesh::FaceHandle f);

  std::vector<NewFace> faces_after_collapse(TriMesh::HalfedgeHandle h) const;
  std::vector<NewFace> faces_after_flip(TriMesh::EdgeHandle e) const;
  bool link_condition_holds(TriMesh::HalfedgeHandle h) const;
  bool collapse_stays_in_plane(TriMesh::HalfedgeHandle h, const std::vector<NewFace>& faces) const;
  bool boundary_curve_kept(TriMesh::HalfedgeHandle h) const;
  bool shapes_acceptable(const std::vector<NewFace>& faces) const;
  bool inside_envelope(const std::vector<NewFace>& faces) const;
  // Envelope verdicts per triangle (corners sorted, see mesh_state_checks.cpp).
  using SortedCorners = std::array<double, 9>;
  struct SortedCornersHash {
    std::size_t operator()(const SortedCorners& key) const;
  };
  static SortedCorners sorted_corners(const Corners& c);
  static Corners corners_of(const SortedCorners& key);
  bool quick_envelope_refusal(const Corners& c) const;
  bool full_envelope_test(const Corners& c) const;

  // Carried points: the envelope bounds only the distance from the output to
  // the input, so on its own it lets a part thinner than epsilon shrink away
  // one collapse at a time. Every removed vertex is carried by a current face
  // within epsilon of it, and an operation passes only if the points carried
  // by the faces it rewrites stay within epsilon of the faces it leaves.
  // (carried_points.cpp)
  std::vector<Vec3d> points_carried_by(const std::vector<TriMesh::FaceHandle>& faces) const;
  bool collapse_keeps_carried_points(TriMesh::HalfedgeHandle h, const std::vector<NewFace>& faces) const;
  bool flip_keeps_carried_points(TriMesh::EdgeHandle e, const std::vector<NewFace>& faces) const;
  std::vector<std::uint32_t> take_carried_points(const std::vector<TriMesh::FaceHandle>& faces);
  void carry_by_nearest(const std::vector<std::uint32_t>& points,
                        const std::vector<TriMesh::FaceHandle>& faces);
  // Signed volumes of the closed components (component_volumes.cpp).
  void build_component_volumes();
  double collapse_volume_change(TriMesh::HalfedgeHandle h) const;
  double flip_volume_change(TriMesh::EdgeHandle e) const;
  bool keeps_enough_volume(TriMesh::VertexHandle v, double change) const;

  /// replaced(face index) tells faces the operation removes or rewrites;
  /// old_faces are their corners.
  template <class Replaced>
  bool faces_apart(const std::vector<NewFace>& faces, const std::vector<Corners>& old_faces,
                   Replaced&& replaced) const;

  TriMesh mesh_;
  DerivedTolerances tolerances_;
  std::vector<Corners> kept_aside_;             // corners of faces OpenMesh rejected
  std::vector<Triangle> kept_aside_triangles_;  // their welded indices
  std::vector<Copies> copies_;                  // per mesh face
  std::size_t duplicate_faces_ = 0;             // input faces that share a mesh face with an earlier one
  std::vector<std::uint8_t> locked_;            // per vertex: never moved or flipped around
  std::vector<std::array<Index, 2>>
      merges_;  // sorted: collapses allowed from a vertex locked by frozen faces only
  std::unique_ptr<envelope::Envelope> envelope_;
  std::unique_ptr<envelope::Envelope> fine_envelope_;      // stage 2: asked only where envelope_ refuses
  std::unique_ptr<envelope::Envelope> boundary_envelope_;  // null when the input has no boundary
  // Vertices never move, so a triangle's envelope verdict never changes; a
  // candidate is checked again every time its neighbourhood changes, mostly
  // with the same new faces. The verdict is a function of the sorted corners
  // alone, so which thread stores it first does not matter (determinism).
  // Two generations bound the memory (bound_caches): trimesh/cycloidal's
  // clean-up asked about 4 million faces, 450 MB of one ever-growing map.
  using Verdicts = tbb::concurrent_unordered_map<SortedCorners, bool, SortedCornersHash>;
  mutable Verdicts envelope_verdicts_;        // stored since the last generation change
  mutable Verdicts older_envelope_verdicts_;  // the generation before, still asked
  std::optional<bool> known_envelope_verdict(const SortedCorners& key) const;
  spatial::BoxGrid grid_;
  std::vector<Quadric> quadrics_;
  std::vector<Vec3d> carried_positions_;                // removed vertices
  std::vector<std::vector<std::uint32_t>> carried_by_;  // per mesh face: indices into carried_positions_
  std::size_t live_faces_ = 0;
  std::vector<std::uint32_t> component_;  // per vertex; collapses and flips never join or split components
  std::vector<double> volume6_;           // per component: six times its signed volume
  std::vector<double> initial_volume6_;   // per component: volume6_ before the first change
  std::vector<std::uint8_t> closed_;      // per component: no boundary edge
};

}  // namespace mr::simplify
