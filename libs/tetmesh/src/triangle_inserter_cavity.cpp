// Stage 4, second half: rebuilding the cavity of one triangle from its
// convex cells (see triangle_inserter.h).

#include "triangle_inserter.h"

#include "inserter_keys.h"

#include <mr/kernel/rounding.h>

#include <algorithm>

namespace mr::tetmesh::detail {

// ------------------------------------------------------------ rebuilding

void TriangleInserter::append_edge_interior(Index u, Index v, std::vector<Index>& out) const {
  const auto it = splits_.find(segment_key(u, v));
  if (it == splits_.end()) return;
  append_edge_interior(u, it->second, out);
  out.push_back(it->second);
  append_edge_interior(it->second, v, out);
}

// The polygon with the flat points of its sides, and per entry the bit set
// of the sides it lies on (corner i is on sides i - 1 and i).
std::vector<Index> TriangleInserter::with_flat_points(const std::vector<Index>& polygon,
                                                      std::vector<std::uint32_t>& sides) const {
  std::vector<Index> result;
  sides.clear();
  const std::size_t n = polygon.size();
  const auto bit = [](std::size_t side) { return side < 32 ? 1u << side : 0u; };
  for (std::size_t i = 0; i < n; ++i) {
    result.push_back(polygon[i]);
    sides.push_back(bit(i) | bit((i + n - 1) % n));
    append_edge_interior(polygon[i], polygon[(i + 1) % n], result);
    sides.resize(result.size(), bit(i));
  }
  return result;
}

// Face k of cavity tet t as polygons oriented out of t.
std::vector<TriangleInserter::Piece> TriangleInserter::face_pieces(Index t, int face) {
  const auto f = mesh_.face_vertices(t, face);
  const auto split = split_faces_.find(sorted_corners(f));
  if (split == split_faces_.end()) {
    const auto ids = mesh_.surface_ids(t, face);
    return {{{f[0], f[1], f[2]}, Ids(ids.begin(), ids.end())}};
  }
  std::vector<Piece> pieces = split->second.pieces;
  if (!same_orientation(split->second.oriented, f)) {
    for (Piece& piece : pieces) std::reverse(piece.corners.begin(), piece.corners.end());
  }
  return pieces;
}

void TriangleInserter::add_polygon(const std::vector<Index>& polygon, const Ids& ids, int plane,
                                   std::vector<CellTriangle>& cell) {
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::uint32_t> sides;
  const std::vector<Index> expanded = with_flat_points(polygon, sides);
  triangulate_convex_polygon(mesh_, expanded, sides, triangles);
  const Ids* stored = nullptr;
  if (!ids.empty()) stored = &ids_storage_.emplace_back(ids);
  for (const auto& triangle : triangles) cell.push_back({triangle, stored, plane});
}

void TriangleInserter::build_cell(std::vector<CellTriangle>& cell, std::vector<ConeTet>& tets) {
  Index steiner = kNoVertex;
  tetrahedralize_convex_cell(mesh_, cell, tets, steiner);
  if (steiner != kNoVertex) {
    note_new_vertex(steiner);
    new_vertices_.insert(steiner);
    ++counters_.steiner_points;
  }
  cell.clear();
}

void TriangleInserter::rebuild_cavity() {
  std::vector<ConeTet> tets;
  std::vector<CellTriangle> cell;
  for (Index t : cavity_) {
    const bool cut = stamped(cut_stamp_, t);
    const std::vector<int> sides = cut ? std::vector<int>{1, -1} : std::vector<int>{0};
    for (int sign : sides) {
      for (int k = 0; k < 4; ++k) {
        for (const Piece& piece : face_pieces(t, k)) {
          if (piece.corners.size() < 3) continue;
          if (sign != 0) {
            int piece_side = 0;
            for (Index v : piece.corners) piece_side = piece_side != 0 ? piece_side : plane_sign(v);
            if (piece_side != sign) continue;
          }
          add_polygon(piece.corners, piece.ids, k, cell);
        }
      }
      if (cut) {
        for (const Piece& piece : section_pieces_.at(t)) {
          std::vector<Index> polygon = piece.corners;
          if (sign < 0) std::reverse(polygon.begin(), polygon.end());
          add_polygon(polygon, piece.ids, 4, cell);  // the section: plane P
        }
      }
      build_cell(cell, tets);
    }
  }

  std::vector<Index> outside;
  for (Index t : cavity_) {
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh_.neighbour(t, k);
      if (n != kNoTet && !stamped(cavity_stamp_, n)) outside.push_back(n);
    }
  }
  for (Index t : cavity_) mesh_.remove_tet(t);
  std::vector<Index> created;
  created.reserve(tets.size());
  for (const ConeTet& tet : tets) {
    const Index t = mesh_.add_tet(tet.corners);
    for (int k = 0; k < 4; ++k) {
      if (tet.face_ids[k] != nullptr) mesh_.set_surface_ids(t, k, *tet.face_ids[k]);
    }
    for (Index v : tet.corners) seed_tet_[v] = t;
    created.push_back(t);
  }
  counters_.cut_tets += cut_tets_.size();
  counters_.rebuilt_tets += cavity_.size();
  counters_.new_tets += created.size();
  round_oversized_points(std::span<const Index>(created.data(), tets.size()));
  created.insert(created.end(), outside.begin(), outside.end());
  mesh_.connect(created);
}

// A cut point on a segment between earlier cut points has coordinates
// several times as long as theirs, and chains of such cuts (faces repeated
// or crossing many times, as in CAD soups) grow them into thousands of bits
// that make every later predicate slow (trimesh/chair_model spent most of
// its time multiplying them). Points past InsertionOptions::max_exact_bits are rounded at once
// when no tet around them inverts; the others wait for the rounding stage
// (rounding every point at once left knots, see rounding_stage.h).
// Points on tracked faces wait too: rounded, they take those faces off
// their plane, and a later triangle in that plane no longer finds them on
// it, so the faces it overlaps miss its mark and the tracked chain opens
// (openscad-nonmanifold-crash: 30 edges of two triangles).
void TriangleInserter::round_oversized_points(std::span<const Index> created) {
  std::vector<Index> oversized;
  for (const Index v : new_vertices_) {
    const HybridPoint& p = mesh_.position(v);
    if (p.is_exact() && bit_size(*p.exact) > max_exact_bits_) oversized.push_back(v);
  }
  if (oversized.empty()) return;
  std::sort(oversized.begin(), oversized.end());
  // Every tet around a new point is new: the stars come from `created`.
  std::vector<std::vector<OppositeFace>> stars(oversized.size());
  std::vector<char> on_tracked_face(oversized.size(), 0);
  for (const Index t : created) {
    const Tet& tet = mesh_.tet(t);
    for (int corner = 0; corner < 4; ++corner) {
      const auto it = std::lower_bound(oversized.begin(), oversized.end(), tet[corner]);
      if (it == oversized.end() || *it != tet[corner]) continue;
      const auto i = static_cast<std::size_t>(it - oversized.begin());
      const auto f = opposite_face(tet, corner);
      stars[i].push_back({&mesh_.position(f[0]), &mesh_.position(f[1]), &mesh_.position(f[2])});
      for (int k = 0; k < 4; ++k) {
        if (k != corner && !mesh_.surface_ids(t, k).empty()) on_tracked_face[i] = 1;
      }
    }
  }
  for (std::size_t i = 0; i < oversized.size(); ++i) {
    if (on_tracked_face[i] != 0) continue;
    if (try_round(mesh_.position(oversized[i]), stars[i])) ++counters_.eagerly_rounded;
  }
}

}  // namespace mr::tetmesh::detail
