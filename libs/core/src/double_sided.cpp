#include <mr/core/double_sided.h>
#include <mr/core/orientation.h>
#include <mr/core/weld.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

namespace mr {
namespace {

using Key = std::array<Index, 3>;

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

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Per face, the smallest face index of its edge-connected component.
std::vector<std::uint32_t> components(const std::vector<Triangle>& faces) {
  UnionFind sets(faces.size());
  std::map<std::pair<Index, Index>, std::uint32_t> first_on_edge;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const auto edge = std::minmax(faces[f][i], faces[f][(i + 1) % 3]);
      const auto [it, inserted] = first_on_edge.try_emplace(edge, f);
      if (!inserted) sets.unite(it->second, f);
    }
  std::vector<std::uint32_t> out(faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f) out[f] = sets.find(f);
  return out;
}

double signed_volume(const TriangleSoup& soup, const std::vector<std::uint32_t>& faces) {
  Vec3d centre = Vec3d::Zero();
  for (std::uint32_t f : faces)
    for (Index v : soup.triangles[f]) centre += soup.positions[v];
  centre /= double(3 * faces.size());
  double volume = 0.0;
  for (std::uint32_t f : faces) {
    const Triangle& t = soup.triangles[f];
    volume += (soup.positions[t[0]] - centre).dot((soup.positions[t[1]] - centre).cross(soup.positions[t[2]] - centre));
  }
  return volume;
}

}  // namespace

std::size_t make_double_sided_components_one_sided(TriangleSoup& soup) {
  const TriangleSoup welded = weld_identical_vertices(soup);
  const std::size_t n = welded.triangles.size();
  std::map<Key, std::array<std::uint32_t, 2>> orientations;  // per sorted triple: copies along, against
  for (const Triangle& t : welded.triangles) ++orientations[sorted(t)][along_sorted(t) ? 0 : 1];
  const auto two_sided = [&](const Triangle& t) {
    const auto& c = orientations[sorted(t)];
    return c[0] > 0 && c[1] > 0;
  };
  const std::vector<std::uint32_t> component = components(welded.triangles);
  std::vector<char> all_two_sided(n, 1);  // per component root
  for (std::size_t f = 0; f < n; ++f)
    if (!two_sided(welded.triangles[f])) all_two_sided[component[f]] = 0;

  // Keep the first copy of each face of a double-sided component.
  std::vector<char> keep(n, 1);
  std::map<Key, char> seen;
  std::size_t dropped = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (!all_two_sided[component[f]]) continue;
    if (!seen.try_emplace(sorted(welded.triangles[f]), 1).second) {
      keep[f] = 0;
      ++dropped;
    }
  }
  // Only closed components: an open double-sided sheet is a wall of no
  // thickness, which the pipeline thickens; made one-sided, its winding
  // number would fill space on one side of it.
  std::map<std::pair<std::uint32_t, std::pair<Index, Index>>, std::uint32_t> edge_uses;  // (component, edge)
  for (std::size_t f = 0; f < n; ++f) {
    if (!keep[f] || !all_two_sided[component[f]]) continue;
    const Triangle& t = welded.triangles[f];
    for (int i = 0; i < 3; ++i) ++edge_uses[{component[f], std::minmax(t[i], t[(i + 1) % 3])}];
  }
  for (const auto& [use, count] : edge_uses)
    if (count % 2 != 0) all_two_sided[use.first] = 0;
  for (std::size_t f = 0; f < n; ++f)
    if (!keep[f] && !all_two_sided[component[f]]) {
      keep[f] = 1;
      --dropped;
    }
  if (dropped == 0) return 0;

  // The kept faces of those components, as a soup of their own: oriented
  // coherently, then each component flipped if it encloses negative volume.
  TriangleSoup sheet;
  sheet.positions = welded.positions;
  std::vector<std::uint32_t> sheet_face;  // index into soup.triangles
  for (std::size_t f = 0; f < n; ++f)
    if (keep[f] && all_two_sided[component[f]]) {
      sheet.triangles.push_back(welded.triangles[f]);
      sheet_face.push_back(static_cast<std::uint32_t>(f));
    }
  orient_coherently(sheet);
  std::map<std::uint32_t, std::vector<std::uint32_t>> by_component;
  for (std::uint32_t i = 0; i < sheet.triangles.size(); ++i) by_component[component[sheet_face[i]]].push_back(i);
  for (const auto& [root, faces] : by_component)
    if (signed_volume(sheet, faces) < 0.0)
      for (std::uint32_t i : faces) std::swap(sheet.triangles[i][1], sheet.triangles[i][2]);

  // Write back on the soup's own indices: a sheet face is the soup face
  // with its corners possibly reversed.
  for (std::uint32_t i = 0; i < sheet.triangles.size(); ++i) {
    Triangle& t = soup.triangles[sheet_face[i]];
    if (along_sorted(sheet.triangles[i]) != along_sorted(welded.triangles[sheet_face[i]])) std::swap(t[1], t[2]);
  }
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
