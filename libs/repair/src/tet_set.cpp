#include "tet_set.h"

#include <mr/core/errors.h>

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <numeric>
#include <tuple>

namespace mr::repair::detail {

Triangle tet_face(const Tet& tet, int k) {
  return {tet[kTetFaces[k][0]], tet[kTetFaces[k][1]], tet[kTetFaces[k][2]]};
}

bool has_corner(const Tet& tet, Index v) { return std::find(tet.begin(), tet.end(), v) != tet.end(); }

double tet_volume(const std::vector<Vec3d>& positions, const Tet& tet) {
  const Vec3d& a = positions[tet[0]];
  return (positions[tet[1]] - a).cross(positions[tet[2]] - a).dot(positions[tet[3]] - a) / 6.0;
}

VertexStars::VertexStars(const std::vector<Tet>& tets, std::size_t vertices)
    : VertexStars(tets, vertices, std::vector<char>(vertices, 1)) {}

VertexStars::VertexStars(const std::vector<Tet>& tets, std::size_t vertices, std::span<const Index> wanted)
    : VertexStars(tets, vertices, [&] {
        std::vector<char> asked(vertices, 0);
        for (Index v : wanted) asked[v] = 1;
        return asked;
      }()) {}

VertexStars::VertexStars(const std::vector<Tet>& tets, std::size_t vertices, const std::vector<char>& asked)
    : offsets_(vertices + 1, 0) {
  for (const Tet& t : tets)
    for (Index v : t)
      if (asked[v] != 0) ++offsets_[v + 1];
  std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
  tets_.resize(offsets_.back());
  std::vector<std::size_t> next(offsets_.begin(), offsets_.end() - 1);
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (Index v : tets[t])
      if (asked[v] != 0) tets_[next[v]++] = static_cast<Index>(t);
}

FaceNeighbours::FaceNeighbours(const std::vector<Tet>& tets) : across_(4 * tets.size(), kNoTet) {
  struct Entry {
    Triangle key;
    Index tet;
    int face;
  };
  std::vector<Entry> entries;
  entries.reserve(4 * tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int k = 0; k < 4; ++k) {
      Triangle key = tet_face(tets[t], k);
      std::sort(key.begin(), key.end());
      entries.push_back({key, static_cast<Index>(t), k});
    }
  // (key, tet) orders the entries totally: the same order whatever the thread count.
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.key, a.tet) < std::tie(b.key, b.tet);
  });
  for (std::size_t i = 0; i < entries.size();) {
    std::size_t j = i + 1;
    while (j < entries.size() && entries[j].key == entries[i].key) ++j;
    if (j - i > 2) throw RunError("repair: three or more tets share a face: the tets are not an embedding");
    if (j - i == 2) {
      across_[4 * std::size_t(entries[i].tet) + entries[i].face] = entries[i + 1].tet;
      across_[4 * std::size_t(entries[i + 1].tet) + entries[i + 1].face] = entries[i].tet;
    }
    i = j;
  }
}

std::vector<FaceRef> boundary_faces(const FaceNeighbours& neighbours, std::span<const TetState> states) {
  std::vector<FaceRef> faces;
  for (std::size_t t = 0; t < states.size(); ++t) {
    if (!in_solid(states[t])) continue;
    for (int k = 0; k < 4; ++k)
      if (on_boundary(neighbours, states, Index(t), k)) faces.push_back({Index(t), k});
  }
  return faces;
}

std::vector<std::vector<Index>> face_connected_classes(const FaceNeighbours& neighbours,
                                                       std::span<const Index> subset) {
  std::vector<Index> members(subset.begin(), subset.end());
  std::sort(members.begin(), members.end());
  std::vector<int> class_of(members.size(), -1);
  std::vector<std::vector<Index>> classes;
  auto position = [&](Index t) {
    const auto it = std::lower_bound(members.begin(), members.end(), t);
    return it != members.end() && *it == t ? std::ptrdiff_t(it - members.begin()) : std::ptrdiff_t(-1);
  };
  for (std::size_t seed = 0; seed < members.size(); ++seed) {
    if (class_of[seed] >= 0) continue;
    const int id = static_cast<int>(classes.size());
    classes.emplace_back();
    std::vector<std::size_t> stack{seed};
    class_of[seed] = id;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      classes[id].push_back(members[i]);
      for (int k = 0; k < 4; ++k) {
        const Index other = neighbours.across(members[i], k);
        if (other == kNoTet) continue;
        const std::ptrdiff_t j = position(other);
        if (j >= 0 && class_of[j] < 0) {
          class_of[j] = id;
          stack.push_back(std::size_t(j));
        }
      }
    }
    std::sort(classes[id].begin(), classes[id].end());
  }
  std::stable_sort(classes.begin(), classes.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return classes;
}

}  // namespace mr::repair::detail
