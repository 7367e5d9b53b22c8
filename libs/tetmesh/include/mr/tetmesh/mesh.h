#pragma once
// The mutable tet mesh the tetrahedralization pipeline works on (stages 3 to
// 6 of DESIGN.md): hybrid vertex positions (doubles, plus a rational while a
// cut point cannot be rounded), per-vertex flags, tets with face-to-face
// adjacency, and per-face marks of the tracked surface carrying the ids of
// the input triangles the face lies on.
//
// Conventions:
// - Every live tet is positively oriented: orient3d(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) > 0,
//   exactly, on the hybrid positions.
// - Face k of a tet is the face opposite its corner k. face_vertices(t, k)
//   orders its corners so that the face normal points out of t.
// - neighbour(t, k) is the tet on the other side of face k, or kNoTet on the
//   hull (the faces of the background box).
// - A tracked-surface mark is stored on both sides of an interior face:
//   set_surface_ids writes both.
// - Removed slots are kept (and reused by later additions) until compact():
//   indices of live elements stay valid across additions and removals.
//
// find_mesh_inconsistency (mesh_check.h) verifies all of this; call it in
// tests and debug builds after each operation that edits the mesh.

#include <mr/kernel/hybrid_point.h>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <vector>

namespace mr::tetmesh {

inline constexpr Index kNoTet = std::numeric_limits<Index>::max();
inline constexpr Index kNoVertex = std::numeric_limits<Index>::max();

/// Vertex flags (a bit set).
enum VertexFlag : std::uint8_t {
  kOnSurface = 1,   ///< a corner of some tracked-surface face
  kOnBoundary = 2,  ///< on an open boundary edge of the input (re-projected when smoothed)
  kLocked = 4,      ///< must not move
  kOnBox = 8,       ///< on the background box: may only slide within its box face(s)
};

/// Old index -> new index after compact(); kNoVertex / kNoTet for removed slots.
struct Compaction {
  std::vector<Index> vertex_map;
  std::vector<Index> tet_map;
};

class Mesh {
 public:
  /// Reserves room for this many vertex and tet slots.
  void reserve(std::size_t vertices, std::size_t tets);

  // ---- vertices ----
  Index add_vertex(const HybridPoint& position, std::uint8_t flags = 0);
  /// Frees the slot. Precondition (checked by the inconsistency finder, not
  /// here): no live tet uses the vertex.
  void remove_vertex(Index v);
  bool vertex_alive(Index v) const { return v < vertex_alive_.size() && vertex_alive_[v]; }
  /// Number of slots, removed ones included: valid indices are below it.
  std::size_t vertex_slots() const { return positions_.size(); }
  std::size_t num_vertices() const { return positions_.size() - free_vertices_.size(); }

  const HybridPoint& position(Index v) const { return positions_[v]; }
  HybridPoint& position(Index v) { return positions_[v]; }
  std::uint8_t flags(Index v) const { return flags_[v]; }
  bool has_flag(Index v, VertexFlag flag) const { return (flags_[v] & flag) != 0; }
  void set_flags(Index v, std::uint8_t flags) { flags_[v] = flags; }
  void add_flags(Index v, std::uint8_t flags) { flags_[v] |= flags; }

  // ---- tets ----
  /// Adds a tet with no neighbours and no marks; connect() or glue() links it.
  /// Throws mr::UsageError if a corner is not a live vertex or corners repeat.
  /// Orientation is not checked here (it is in find_mesh_inconsistency).
  Index add_tet(const Tet& corners);
  /// Frees the slot. Neighbours stop pointing at it (their faces become free,
  /// and keep their surface marks).
  void remove_tet(Index t);
  bool tet_alive(Index t) const { return t < tets_.size() && tets_[t].alive; }
  std::size_t tet_slots() const { return tets_.size(); }
  std::size_t num_tets() const { return tets_.size() - free_tets_.size(); }

  const Tet& tet(Index t) const { return tets_[t].corners; }
  Index neighbour(Index t, int face) const { return tets_[t].neighbours[face]; }
  /// Corners of face k, ordered so that its normal points out of the tet.
  std::array<Index, 3> face_vertices(Index t, int face) const;
  /// The face of `t` opposite corner vertex v, or -1 if v is not a corner.
  int corner_of(Index t, Index v) const;
  /// The face of `t` shared with tet u, or -1 if they are not neighbours.
  int face_towards(Index t, Index u) const;

  /// Makes face ft of t and face fu of u neighbours. Precondition: they have
  /// the same three corners (checked by find_mesh_inconsistency).
  void glue(Index t, int ft, Index u, int fu);
  /// Unlinks face f of t from its neighbour (both sides).
  void detach(Index t, int f);
  /// Links every free face (no neighbour) of `tets` to the free face with the
  /// same three corners among them: the step after replacing a cavity, with
  /// `tets` = the new tets plus the tets around the cavity. A surface mark on
  /// one side only is copied to the other side. Throws mr::UsageError when
  /// three or more free faces share corners.
  void connect(std::span<const Index> tets);
  /// Recomputes the adjacency of the whole mesh from scratch (parallel sort);
  /// surface marks are kept and made two-sided as in connect().
  void rebuild_adjacency();

  // ---- tracked surface ----
  bool is_surface_face(Index t, int face) const { return tets_[t].marks[face] != kNoMark; }
  /// Input triangle ids of face k (sorted, unique); empty when not tracked.
  std::span<const std::uint32_t> surface_ids(Index t, int face) const;
  /// Sets the ids of the face on both of its sides and flags its corners
  /// kOnSurface. `ids` need not be sorted; empty clears the mark (flags stay).
  void set_surface_ids(Index t, int face, std::span<const std::uint32_t> ids);
  /// Opaque handle of a face's id set; equal handles mean equal sets.
  std::uint32_t surface_handle(Index t, int face) const { return tets_[t].marks[face]; }

  /// Drops removed slots, renumbering live vertices and tets in their current
  /// order; adjacency is remapped. Returns the maps from old to new indices.
  Compaction compact();

 private:
  static constexpr std::uint32_t kNoMark = 0;

  struct TetRecord {
    Tet corners{};
    std::array<Index, 4> neighbours{kNoTet, kNoTet, kNoTet, kNoTet};
    std::array<std::uint32_t, 4> marks{};  // handles into mark_sets_ (kNoMark: untracked)
    bool alive = false;
  };

  struct FaceSlot;  // a free face waiting for its twin (mesh.cpp)

  std::uint32_t intern(std::vector<std::uint32_t> ids);
  void set_mark_one_side(Index t, int face, std::uint32_t handle) { tets_[t].marks[face] = handle; }
  void link_matching_faces(std::vector<FaceSlot>& faces);

  std::vector<HybridPoint> positions_;
  std::vector<std::uint8_t> flags_;
  std::vector<char> vertex_alive_;
  std::vector<Index> free_vertices_;

  std::vector<TetRecord> tets_;
  std::vector<Index> free_tets_;

  // Interned id sets: handle h > 0 names mark_sets_[h - 1]. Singletons are
  // cached by triangle id so that the common case needs no map lookup.
  std::vector<std::vector<std::uint32_t>> mark_sets_;
  std::vector<std::uint32_t> singleton_handles_;
  std::map<std::vector<std::uint32_t>, std::uint32_t> multi_handles_;
};

}  // namespace mr::tetmesh
