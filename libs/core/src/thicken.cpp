#include <mr/core/thicken.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <utility>

namespace mr {
namespace {

void add_prism(const std::array<Vec3d, 3>& corner, const Vec3d& offset, TriangleSoup& out) {
  const auto first = static_cast<Index>(out.positions.size());
  for (const Vec3d& p : corner) out.positions.push_back(p - offset);  // bottom: first + i
  for (const Vec3d& p : corner) out.positions.push_back(p + offset);  // top: first + 3 + i
  const auto bottom = [&](int i) { return first + Index(i); };
  const auto top = [&](int i) { return first + 3 + Index(i); };
  out.triangles.push_back({top(0), top(1), top(2)});
  out.triangles.push_back({bottom(0), bottom(2), bottom(1)});
  // The wall on edge (i, j) faces away from the third corner: for a
  // counter-clockwise triangle that is (j - i) x normal.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    out.triangles.push_back({bottom(i), bottom(j), top(j)});
    out.triangles.push_back({bottom(i), top(j), top(i)});
  }
}

/// The prism of a triangle with a normal (one of non-zero area in doubles).
void add_prism_if_oriented(const std::array<Vec3d, 3>& corner, double half_thickness, TriangleSoup& out) {
  const Vec3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
  const double length = normal.norm();
  if (length > 0.0) add_prism(corner, normal * (half_thickness / length), out);
}

/// The parallelepiped origin + [0,1] e0 + [0,1] e1 + [0,1] e2, oriented
/// outward when (e0 x e1) . e2 > 0.
void add_box(const Vec3d& origin, const Vec3d& e0, const Vec3d& e1, const Vec3d& e2, TriangleSoup& out) {
  const auto first = static_cast<Index>(out.positions.size());
  for (int corner = 0; corner < 8; ++corner)  // bit k of corner: e_k added
    out.positions.push_back(origin + double(corner & 1) * e0 + double((corner >> 1) & 1) * e1 +
                            double((corner >> 2) & 1) * e2);
  static constexpr std::array<std::array<Index, 3>, 12> faces{{{0, 2, 1},
                                                               {1, 2, 3},
                                                               {4, 5, 6},
                                                               {5, 7, 6},
                                                               {0, 1, 5},
                                                               {0, 5, 4},
                                                               {2, 6, 7},
                                                               {2, 7, 3},
                                                               {0, 4, 6},
                                                               {0, 6, 2},
                                                               {1, 3, 7},
                                                               {1, 7, 5}}};
  for (const auto& f : faces) out.triangles.push_back({first + f[0], first + f[1], first + f[2]});
}

/// A box around the segment ab, `radius` from its line and past its ends.
void add_edge_box(const Vec3d& a, const Vec3d& b, double radius, TriangleSoup& out) {
  Vec3d along = b - a;
  const double length = along.norm();
  along = length > 0.0 ? Vec3d(along / length) : Vec3d::UnitX();
  // Any direction across the edge: the axis least along it, made perpendicular.
  Eigen::Index axis = 0;
  along.cwiseAbs().minCoeff(&axis);
  const Vec3d across = along.cross(Vec3d::Unit(axis)).normalized();
  const Vec3d up = along.cross(across);  // (along x across) . up > 0
  add_box(a - radius * (along + across + up), (length + 2 * radius) * along, 2 * radius * across,
          2 * radius * up, out);
}

/// For each vertex used by a triangle, the first one (in triangle order) in
/// its cell of a grid `cell` wide.
std::vector<Index> merge_corners_in_cells(const TriangleSoup& soup, double cell) {
  std::map<std::array<double, 3>, Index> first_in_cell;
  std::vector<Index> merged(soup.positions.size());
  for (const Triangle& t : soup.triangles)
    for (Index v : t) {
      const Vec3d& p = soup.positions[v];
      const std::array<double, 3> key{std::floor(p.x() / cell), std::floor(p.y() / cell),
                                      std::floor(p.z() / cell)};
      merged[v] = first_in_cell.try_emplace(key, v).first->second;
    }
  return merged;
}

}  // namespace

// Corners in one cell of a grid radius/4 wide are merged first, so that
// edges and triangles that differ by less give one piece, not several
// nearly coincident ones, which crossing at tiny angles cost the insertion
// tens of thousands of cut points (fuzzer inputs of 11 triangles: 19 s). A
// point moves by at most the cell's diagonal.
TriangleSoup fatten_sheets(const TriangleSoup& soup, double radius) {
  const std::vector<Index> merged = merge_corners_in_cells(soup, radius / 4);
  std::set<std::array<Index, 3>> triangles;  // sorted: both orientations make one prism
  std::set<std::pair<Index, Index>> edges;
  for (const Triangle& t : soup.triangles) {
    std::array<Index, 3> c{merged[t[0]], merged[t[1]], merged[t[2]]};
    for (int i = 0; i < 3; ++i) edges.emplace(std::minmax(c[i], c[(i + 1) % 3]));
    std::sort(c.begin(), c.end());
    if (c[0] != c[1] && c[1] != c[2]) triangles.insert(c);
  }
  TriangleSoup out;
  for (const auto& c : triangles)
    add_prism_if_oriented({soup.positions[c[0]], soup.positions[c[1]], soup.positions[c[2]]}, radius, out);
  for (const auto& [u, v] : edges) add_edge_box(soup.positions[u], soup.positions[v], radius, out);
  return out;
}

TriangleSoup thicken_sheets(const TriangleSoup& soup, double half_thickness) {
  TriangleSoup out;
  out.positions.reserve(6 * soup.triangles.size());
  out.triangles.reserve(8 * soup.triangles.size());
  for (const Triangle& t : soup.triangles) {
    add_prism_if_oriented({soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]}, half_thickness,
                          out);
  }
  return out;
}

}  // namespace mr
