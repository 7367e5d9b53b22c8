#include <mr/core/orientation.h>
#include <mr/core/weld.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <stdexcept>
#include <tuple>

namespace mr {
namespace {

// One directed use of an undirected edge by a face.
struct EdgeUse {
  Index lo, hi;
  Index opposite;  // the face's third corner
  std::uint32_t face;
  bool forward;  // the face runs lo -> hi

  bool same_edge(const EdgeUse& o) const { return lo == o.lo && hi == o.hi; }
};

// For every face, its neighbours across manifold edges and whether the two
// faces currently run along that edge in the same direction (inconsistent).
struct Adjacency {
  struct Link {
    std::uint32_t face;
    bool same_direction;
  };
  std::vector<std::vector<Link>> links;
};

// `welded` has the soup's triangles, in order, on welded vertices.
Adjacency manifold_adjacency(const TriangleSoup& welded) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * welded.triangles.size());
  for (std::uint32_t f = 0; f < welded.triangles.size(); ++f) {
    const Triangle& c = welded.triangles[f];
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    for (int i = 0; i < 3; ++i) {
      const Index a = c[i], b = c[(i + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), c[(i + 2) % 3], f, a < b});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  Adjacency adjacency;
  adjacency.links.resize(welded.triangles.size());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].same_edge(uses[i])) ++j;
    // Two copies of one triangle say nothing about each other's orientation.
    if (j - i == 2 && uses[i].opposite != uses[i + 1].opposite) {
      const bool same = uses[i].forward == uses[i + 1].forward;
      adjacency.links[uses[i].face].push_back({uses[i + 1].face, same});
      adjacency.links[uses[i + 1].face].push_back({uses[i].face, same});
    }
    i = j;
  }
  return adjacency;
}

double face_area(const TriangleSoup& soup, const Triangle& t) {
  const Vec3d& a = soup.positions[t[0]];
  return 0.5 * (soup.positions[t[1]] - a).cross(soup.positions[t[2]] - a).norm();
}

}  // namespace

OrientationStats orient_coherently(TriangleSoup& soup) {
  std::vector<double> areas(soup.triangles.size());
  for (std::size_t f = 0; f < areas.size(); ++f) areas[f] = face_area(soup, soup.triangles[f]);
  return orient_coherently(soup, areas);
}

OrientationStats orient_coherently(TriangleSoup& soup, std::span<const double> votes) {
  if (votes.size() != soup.triangles.size()) {
    throw std::invalid_argument("orient_coherently: one vote per triangle expected");
  }
  OrientationStats stats;
  // Unwelded copies of a vertex (STL) must count as one.
  const Adjacency adjacency = manifold_adjacency(weld_identical_vertices(soup));
  constexpr std::int8_t kUnvisited = -1;
  std::vector<std::int8_t> flip(soup.triangles.size(), kUnvisited);
  std::vector<std::uint32_t> patch, queue;
  for (std::uint32_t seed = 0; seed < soup.triangles.size(); ++seed) {
    if (flip[seed] != kUnvisited) continue;
    ++stats.patches;
    patch.clear();
    queue.assign(1, seed);
    flip[seed] = 0;
    // Breadth-first over manifold edges: a neighbour running the shared edge
    // the same way as its (possibly flipped) parent must be flipped.
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::uint32_t f = queue[head];
      patch.push_back(f);
      for (const Adjacency::Link& link : adjacency.links[f]) {
        const std::int8_t wanted = static_cast<std::int8_t>(flip[f] ^ (link.same_direction ? 1 : 0));
        if (flip[link.face] == kUnvisited) {
          flip[link.face] = wanted;
          queue.push_back(link.face);
        } else if (flip[link.face] != wanted && f < link.face) {
          ++stats.conflicts;
        }
      }
    }
    // Votes for the orientation as it is, if flip[] is applied.
    double support = 0.0;
    for (const std::uint32_t f : patch) support += flip[f] ? -votes[f] : votes[f];
    const bool invert = support < 0.0;
    for (const std::uint32_t f : patch) {
      if ((flip[f] != 0) == invert) continue;
      std::swap(soup.triangles[f][1], soup.triangles[f][2]);
      ++stats.flipped;
    }
  }
  return stats;
}

}  // namespace mr
