#include "filled_surface.h"
#include "mesh_keys.h"

#include <mr/kernel/intersections.h>
#include <mr/kernel/predicates.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>

namespace mr::hole_fill::detail {
namespace {

// Twice the mean edge length of the non-degenerate faces: the grid's cell.
double typical_cell(const TriangleSoup& soup) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const Triangle& t : soup.triangles)
    for (int i = 0; i < 3; ++i) {
      const double l = (soup.positions[t[i]] - soup.positions[t[(i + 1) % 3]]).norm();
      if (l > 0.0) sum += l, ++count;
    }
  return count ? 2.0 * sum / double(count) : 1.0;
}

struct Box {
  Vec3d lo, hi;
};

Box box_of(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

bool boxes_overlap(const Box& a, const Box& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

}  // namespace

std::size_t FilledSurface::PositionHash::operator()(const Vec3d& p) const {
  std::uint64_t h = 0;
  for (int i = 0; i < 3; ++i) h = h * 0x9E3779B97F4A7C15ull + std::bit_cast<std::uint64_t>(p[i] + 0.0);
  return std::size_t(h ^ (h >> 29));
}

FilledSurface::FilledSurface(TriangleSoup welded) : soup_(std::move(welded)) {
  cell_size_ = typical_cell(soup_);
  // The grid starts a cell below the lowest corner: positions below its
  // origin all land in its first layer of cells. (It started at the first
  // vertex, which in a shuffled soup lies mid-model: the holes-only check of
  // a 287,896-face soup took 42 s in 649 cells of up to 84,373 entries.)
  const Vec3d lowest = soup_.positions.empty() ? Vec3d::Zero() : bounding_box(soup_).min();
  boxes_ = spatial::BoxGrid(lowest - Vec3d::Constant(cell_size_), cell_size_);
  positions_.insert(soup_.positions.begin(), soup_.positions.end());
  for (std::uint32_t f = 0; f < soup_.triangles.size(); ++f) insert_face(f);
}

void FilledSurface::insert_face(std::uint32_t face) {
  const Triangle& t = soup_.triangles[face];
  if (repeats_a_vertex(t)) return;
  for (int i = 0; i < 3; ++i) ++edge_faces_[edge_key(t[i], t[(i + 1) % 3])];
  const Box b = box_of(soup_.positions[t[0]], soup_.positions[t[1]], soup_.positions[t[2]]);
  boxes_.insert(face, b.lo, b.hi);
}

const Vec3d& FilledSurface::position(Index v, const GlobalPatch& patch) const {
  return v < soup_.positions.size() ? soup_.positions[v] : patch.new_positions[v - soup_.positions.size()];
}

std::string FilledSurface::vertex_refusal(const GlobalPatch& patch) const {
  std::unordered_set<Vec3d, PositionHash> seen;
  for (const Vec3d& p : patch.new_positions)
    if (positions_.count(p) || !seen.insert(p).second) return "a new vertex lands on another vertex";
  for (const Triangle& t : patch.faces)
    if (repeats_a_vertex(t) || collinear(position(t[0], patch), position(t[1], patch), position(t[2], patch)))
      return "a face is degenerate";
  return {};
}

std::string FilledSurface::edge_refusal(const GlobalPatch& patch) const {
  std::unordered_map<std::uint64_t, int> uses;
  for (const Triangle& t : patch.faces)
    for (int i = 0; i < 3; ++i) ++uses[edge_key(t[i], t[(i + 1) % 3])];
  for (const auto& [edge, count] : uses) {
    const auto existing = edge_faces_.find(edge);
    if (count + (existing == edge_faces_.end() ? 0 : existing->second) > 2)
      return "an edge would have more than two faces";
  }
  return {};
}

std::string FilledSurface::intersection_refusal(const GlobalPatch& patch) const {
  std::vector<Box> patch_boxes;
  for (const Triangle& t : patch.faces)
    patch_boxes.push_back(box_of(position(t[0], patch), position(t[1], patch), position(t[2], patch)));
  std::vector<std::uint32_t> near;
  for (std::size_t i = 0; i < patch.faces.size(); ++i) {
    const Triangle& t = patch.faces[i];
    const Vec3d &p = position(t[0], patch), &q = position(t[1], patch), &r = position(t[2], patch);
    boxes_.query(patch_boxes[i].lo, patch_boxes[i].hi, near);
    for (std::uint32_t f : near) {
      const Triangle& s = soup_.triangles[f];
      const Vec3d &a = soup_.positions[s[0]], &b = soup_.positions[s[1]], &c = soup_.positions[s[2]];
      if (collinear(a, b, c)) continue;  // an input's degenerate face: not ours to judge
      if (intersect_triangles(p, q, r, a, b, c).improper()) return "a face meets the surface";
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (!boxes_overlap(patch_boxes[i], patch_boxes[j])) continue;
      const Triangle& s = patch.faces[j];
      if (intersect_triangles(p, q, r, position(s[0], patch), position(s[1], patch), position(s[2], patch))
              .improper())
        return "the patch meets itself";
    }
  }
  return {};
}

std::string FilledSurface::refusal(const GlobalPatch& patch) const {
  if (std::string why = vertex_refusal(patch); !why.empty()) return why;
  if (std::string why = edge_refusal(patch); !why.empty()) return why;
  return intersection_refusal(patch);
}

bool FilledSurface::meets_itself() const {
  std::atomic<bool> met{false};
  tbb::parallel_for(
      tbb::blocked_range<std::uint32_t>(0, std::uint32_t(soup_.triangles.size()), 256),
      [&](const tbb::blocked_range<std::uint32_t>& range) {
        std::vector<std::uint32_t> near;
        for (std::uint32_t f = range.begin(); f != range.end() && !met; ++f) {
          const Triangle& t = soup_.triangles[f];
          const Vec3d &p = soup_.positions[t[0]], &q = soup_.positions[t[1]], &r = soup_.positions[t[2]];
          if (repeats_a_vertex(t) || collinear(p, q, r)) continue;
          const Box b = box_of(p, q, r);
          boxes_.query(b.lo, b.hi, near);
          for (std::uint32_t g : near) {
            if (g <= f) continue;
            const Triangle& s = soup_.triangles[g];
            const Vec3d &a = soup_.positions[s[0]], &c = soup_.positions[s[1]], &d = soup_.positions[s[2]];
            if (collinear(a, c, d)) continue;
            if (intersect_triangles(p, q, r, a, c, d).improper()) met = true;
          }
        }
      });
  return met;
}

void FilledSurface::add(const GlobalPatch& patch) {
  soup_.positions.insert(soup_.positions.end(), patch.new_positions.begin(), patch.new_positions.end());
  positions_.insert(patch.new_positions.begin(), patch.new_positions.end());
  for (const Triangle& t : patch.faces) {
    soup_.triangles.push_back(t);
    insert_face(std::uint32_t(soup_.triangles.size() - 1));
  }
}

}  // namespace mr::hole_fill::detail
