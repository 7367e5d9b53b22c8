#include <mr/core/double_sided.h>
#include <mr/core/orientation.h>
#include <mr/core/union_find.h>
#include <mr/core/weld.h>

#include <algorithm>
#include <map>
#include <utility>

namespace mr {
namespace {

using Key = std::array<Index, 3>;
using Edge = std::pair<Index, Index>;

Key sorted(const Triangle& t) {
  Key k{t[0], t[1], t[2]};
  std::sort(k.begin(), k.end());
  return k;
}

// Whether t runs the same way round as its sorted corners.
bool along_sorted(const Triangle& t) {
  const Key k = sorted(t);
  for (int r = 0; r < 3; ++r)
    if (t[r] == k[0]) return t[(r + 1) % 3] == k[1];
  return true;
}

Edge edge(const Triangle& t, int i) { return std::minmax(t[i], t[(i + 1) % 3]); }

// Per face, a representative face of its edge-connected component.
std::vector<std::size_t> components(const std::vector<Triangle>& faces) {
  UnionFind sets(faces.size());
  std::map<Edge, std::size_t> first_on_edge;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const auto [it, inserted] = first_on_edge.try_emplace(edge(faces[f], i), f);
      if (!inserted) sets.unite(it->second, f);
    }
  std::vector<std::size_t> out(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) out[f] = sets.find(f);
  return out;
}

// Per face of `welded`, whether it is the first copy of its vertex triple.
std::vector<char> first_copies(const std::vector<Triangle>& faces) {
  std::vector<char> first(faces.size(), 0);
  std::map<Key, char> seen;
  for (std::size_t f = 0; f < faces.size(); ++f) first[f] = seen.try_emplace(sorted(faces[f]), 1).second;
  return first;
}

// Per component representative: every face is there in both orientations,
// and the first copies close up (every edge used an even number of times).
std::vector<char> closed_double_sided(const std::vector<Triangle>& faces,
                                      const std::vector<std::size_t>& component,
                                      const std::vector<char>& first) {
  std::map<Key, std::array<std::size_t, 2>> orientations;  // per vertex triple: copies along, against
  for (const Triangle& t : faces) ++orientations[sorted(t)][along_sorted(t) ? 0 : 1];
  std::vector<char> eligible(faces.size(), 1);
  std::map<std::pair<std::size_t, Edge>, std::size_t> edge_uses;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& copies = orientations[sorted(faces[f])];
    if (copies[0] == 0 || copies[1] == 0) eligible[component[f]] = 0;
    if (first[f])
      for (int i = 0; i < 3; ++i) ++edge_uses[{component[f], edge(faces[f], i)}];
  }
  for (const auto& [use, count] : edge_uses)
    if (count % 2 != 0) eligible[use.first] = 0;
  return eligible;
}

double signed_volume(const TriangleSoup& soup, const std::vector<std::size_t>& faces) {
  Vec3d centre = Vec3d::Zero();
  for (std::size_t f : faces)
    for (Index v : soup.triangles[f]) centre += soup.positions[v];
  centre /= double(3 * faces.size());
  double volume = 0.0;
  for (std::size_t f : faces) {
    const Triangle& t = soup.triangles[f];
    volume += (soup.positions[t[0]] - centre)
                  .dot((soup.positions[t[1]] - centre).cross(soup.positions[t[2]] - centre));
  }
  return volume;
}

// Orients `faces` of `welded` (first copies of eligible components)
// coherently, each component outward; returns per face whether it must be
// reversed.
std::vector<char> outward_flips(const TriangleSoup& welded, const std::vector<std::size_t>& faces,
                                const std::vector<std::size_t>& component) {
  TriangleSoup sheet;
  sheet.positions = welded.positions;
  for (std::size_t f : faces) sheet.triangles.push_back(welded.triangles[f]);
  orient_coherently(sheet);
  std::map<std::size_t, std::vector<std::size_t>> by_component;  // sheet face indices
  for (std::size_t i = 0; i < faces.size(); ++i) by_component[component[faces[i]]].push_back(i);
  for (const auto& [root, members] : by_component)
    if (signed_volume(sheet, members) < 0.0)
      for (std::size_t i : members) std::swap(sheet.triangles[i][1], sheet.triangles[i][2]);
  std::vector<char> flip(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i)
    flip[i] = along_sorted(sheet.triangles[i]) != along_sorted(welded.triangles[faces[i]]);
  return flip;
}

}  // namespace

std::size_t make_double_sided_components_one_sided(TriangleSoup& soup) {
  const TriangleSoup welded = weld_identical_vertices(soup);
  const std::size_t n = welded.triangles.size();
  const std::vector<std::size_t> component = components(welded.triangles);
  const std::vector<char> first = first_copies(welded.triangles);
  const std::vector<char> eligible = closed_double_sided(welded.triangles, component, first);

  std::vector<char> keep(n, 1);
  std::vector<std::size_t> one_sided;  // the first copies of eligible components
  for (std::size_t f = 0; f < n; ++f) {
    if (!eligible[component[f]]) continue;
    if (first[f])
      one_sided.push_back(f);
    else
      keep[f] = 0;
  }
  const std::size_t dropped = n - static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1));
  if (dropped == 0) return 0;

  // welded.triangles[f] is soup.triangles[f] on welded indices, corner for corner.
  const std::vector<char> flip = outward_flips(welded, one_sided, component);
  for (std::size_t i = 0; i < one_sided.size(); ++i)
    if (flip[i]) std::swap(soup.triangles[one_sided[i]][1], soup.triangles[one_sided[i]][2]);
  std::size_t kept = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (!keep[f]) continue;
    soup.triangles[kept] = soup.triangles[f];
    if (soup.has_face_regions()) soup.face_regions[kept] = soup.face_regions[f];
    ++kept;
  }
  soup.triangles.resize(kept);
  if (soup.has_face_regions()) soup.face_regions.resize(kept);
  return dropped;
}

}  // namespace mr

namespace mr {

std::size_t drop_repeated_faces(TriangleSoup& soup) {
  const TriangleSoup welded = weld_identical_vertices(soup);
  std::map<std::pair<Key, bool>, char> seen;
  std::size_t kept = 0;
  for (std::size_t f = 0; f < welded.triangles.size(); ++f) {
    const Triangle& t = welded.triangles[f];
    if (!seen.try_emplace({sorted(t), along_sorted(t)}, 1).second) continue;
    soup.triangles[kept] = soup.triangles[f];
    if (soup.has_face_regions()) soup.face_regions[kept] = soup.face_regions[f];
    ++kept;
  }
  const std::size_t dropped = soup.triangles.size() - kept;
  soup.triangles.resize(kept);
  if (soup.has_face_regions()) soup.face_regions.resize(kept);
  return dropped;
}

}  // namespace mr
