#include <mr/hole_fill/redundant_faces.h>

#include "mesh_keys.h"

#include <mr/kernel/predicates.h>

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

namespace mr::hole_fill {
namespace {

// Whether b lies in the closed box of a and c: for three distinct points on
// a line, true of the middle one only (exact comparisons of doubles).
bool between(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  for (int axis = 0; axis < 3; ++axis)
    if (b[axis] < std::min(a[axis], c[axis]) || b[axis] > std::max(a[axis], c[axis])) return false;
  return true;
}

struct CornerSetHash {
  std::size_t operator()(const std::array<Index, 3>& c) const {
    return std::hash<std::uint64_t>()((std::uint64_t(c[0]) * 0x9E3779B97F4A7C15ull) ^
                                      (std::uint64_t(c[1]) << 21) ^ (std::uint64_t(c[2]) << 42) ^ c[2]);
  }
};

// The faces of a welded surface, with the face on each directed edge, as
// faces are dropped and split.
class EdgeFaces {
 public:
  explicit EdgeFaces(TriangleSoup welded) : soup_(std::move(welded)), alive_(soup_.triangles.size(), 1) {
    for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
      if (!detail::repeats_a_vertex(soup_.triangles[f]) && !link(f)) manifold_ = false;
  }

  bool manifold() const { return manifold_; }
  const TriangleSoup& soup() const { return soup_; }
  bool alive(std::size_t f) const { return alive_[f] != 0; }

  void drop(std::size_t f) {
    if (!detail::repeats_a_vertex(soup_.triangles[f])) unlink(f);
    alive_[f] = 0;
  }

  /// The face on the directed edge a -> b, or none (-1).
  std::ptrdiff_t face_on(Index a, Index b) const {
    const auto it = face_of_.find(detail::directed_edge_key(a, b));
    return it == face_of_.end() ? -1 : static_cast<std::ptrdiff_t>(it->second);
  }

  /// Splits face f, whose edge a -> b is its corner `k`'s next edge, at m:
  /// (a, m, c) takes f's place and (m, b, c) is added.
  void split(std::size_t f, int k, Index m) {
    const Triangle t = soup_.triangles[f];
    const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    unlink(f);
    soup_.triangles[f] = {a, m, c};
    soup_.triangles.push_back({m, b, c});
    alive_.push_back(1);
    manifold_ &= link(f) & link(soup_.triangles.size() - 1);
  }

  TriangleSoup release() && {
    TriangleSoup out;
    out.positions = std::move(soup_.positions);
    for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
      if (alive_[f]) out.triangles.push_back(soup_.triangles[f]);
    return out;
  }

 private:
  // False when a directed edge already had a face (an edge of more than two
  // faces, or two faces that disagree on its direction).
  bool link(std::size_t f) {
    bool fresh = true;
    const Triangle& t = soup_.triangles[f];
    for (int i = 0; i < 3; ++i)
      fresh &= face_of_.try_emplace(detail::directed_edge_key(t[i], t[(i + 1) % 3]), f).second;
    return fresh;
  }

  void unlink(std::size_t f) {
    const Triangle& t = soup_.triangles[f];
    for (int i = 0; i < 3; ++i) {
      const auto it = face_of_.find(detail::directed_edge_key(t[i], t[(i + 1) % 3]));
      if (it != face_of_.end() && it->second == f) face_of_.erase(it);
    }
  }

  TriangleSoup soup_;
  std::vector<char> alive_;
  std::unordered_map<std::uint64_t, std::size_t> face_of_;
  bool manifold_ = true;
};

// Takes out collinear face f (alive, three distinct corners): the face
// across its longest edge is split at the middle corner. False, changing
// nothing, when that face is itself degenerate (a later round may have
// split it by then).
bool take_out_collinear(EdgeFaces& faces, std::size_t f, ZeroAreaRemoval& removal) {
  const Triangle t = faces.soup().triangles[f];
  const auto& p = faces.soup().positions;
  for (int k = 0; k < 3; ++k) {
    const Index a = t[k], b = t[(k + 1) % 3], middle = t[(k + 2) % 3];
    if (!between(p[a], p[middle], p[b])) continue;
    const std::ptrdiff_t across = faces.face_on(b, a);
    if (across < 0) {  // a border edge: what f leaves open is the hole's
      faces.drop(f);
      ++removal.dropped;
      return true;
    }
    const Triangle& g = faces.soup().triangles[static_cast<std::size_t>(across)];
    if (detail::sorted_corners(g) == detail::sorted_corners(t)) {  // f and g enclose nothing: both go
      faces.drop(f);
      faces.drop(static_cast<std::size_t>(across));
      removal.dropped += 2;
      return true;
    }
    if (collinear(p[g[0]], p[g[1]], p[g[2]])) return false;
    int at = 0;
    while (g[at] != b) ++at;  // g runs b -> a
    faces.drop(f);
    faces.split(static_cast<std::size_t>(across), at, middle);
    ++removal.dropped;
    ++removal.split;
    return true;
  }
  return false;  // unreachable for distinct collinear corners
}

bool zero_area(const TriangleSoup& soup, const Triangle& t) {
  return detail::repeats_a_vertex(t) ||
         collinear(soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]);
}

}  // namespace

std::size_t remove_repeated_faces(TriangleSoup& welded) {
  std::unordered_set<std::array<Index, 3>, CornerSetHash> seen;
  seen.reserve(welded.triangles.size());
  const std::size_t before = welded.triangles.size();
  std::erase_if(welded.triangles,
                [&](const Triangle& t) { return !seen.insert(detail::sorted_corners(t)).second; });
  return before - welded.triangles.size();
}

ZeroAreaRemoval remove_zero_area_faces(TriangleSoup welded) {
  ZeroAreaRemoval removal;
  const auto& triangles = welded.triangles;
  if (std::none_of(triangles.begin(), triangles.end(),
                   [&](const Triangle& t) { return zero_area(welded, t); })) {
    removal.surface = std::move(welded);
    return removal;
  }
  EdgeFaces faces(std::move(welded));
  std::vector<std::size_t> pending;
  const std::size_t n = faces.soup().triangles.size();
  for (std::size_t f = 0; f < n && faces.manifold(); ++f) {
    const Triangle& t = faces.soup().triangles[f];
    if (detail::repeats_a_vertex(t)) {
      faces.drop(f);
      ++removal.dropped;
    } else if (zero_area(faces.soup(), t)) {
      pending.push_back(f);
    }
  }
  // Each round takes out at least one face or stops, and a split makes no
  // collinear face (its new corner is off the line of the edge it joins).
  for (bool progress = true; progress && !pending.empty() && faces.manifold();) {
    progress = false;
    std::vector<std::size_t> left;
    for (const std::size_t f : pending) {
      if (!faces.alive(f)) continue;  // went with its mirror image
      if (take_out_collinear(faces, f, removal))
        progress = true;
      else
        left.push_back(f);
    }
    pending = std::move(left);
  }
  removal.left = pending.size();
  removal.surface = std::move(faces).release();
  return removal;
}

}  // namespace mr::hole_fill
