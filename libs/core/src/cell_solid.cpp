// The union of the grid cells a soup meets, as a closed surface: for inputs
// a few epsilons across whose prisms would be needles (thicken.h).

#include <mr/core/thicken.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

namespace mr {
namespace {

using CellIndex = std::array<std::int64_t, 3>;

/// Whether the triangle meets the box centred at `centre` with half-size `half`:
/// the separating axis test (the box's axes, the triangle's normal, and each
/// edge crossed with each box axis). A zero axis separates nothing, so
/// degenerate triangles are tested as their segment or point. Floating point:
/// this only chooses cells, it decides no topology.
bool triangle_meets_box(const std::array<Vec3d, 3>& triangle, const Vec3d& centre, double half) {
  const std::array<Vec3d, 3> v{triangle[0] - centre, triangle[1] - centre, triangle[2] - centre};
  const auto separates = [&](const Vec3d& axis) {
    const double p0 = v[0].dot(axis), p1 = v[1].dot(axis), p2 = v[2].dot(axis);
    const double reach = half * axis.cwiseAbs().sum();
    return std::min({p0, p1, p2}) > reach || std::max({p0, p1, p2}) < -reach;
  };
  for (int k = 0; k < 3; ++k)
    if (separates(Vec3d::Unit(k))) return false;
  const std::array<Vec3d, 3> edge{v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (separates(edge[0].cross(edge[1]))) return false;
  for (const Vec3d& e : edge)
    for (int k = 0; k < 3; ++k)
      if (separates(e.cross(Vec3d::Unit(k)))) return false;
  return true;
}

/// Cells are counted from `origin` (the corner of the input's box, so that
/// the indices stay small wherever the input lies).
std::set<CellIndex> cells_met(const TriangleSoup& soup, const Vec3d& origin, double cell) {
  std::set<CellIndex> cells;
  // A hair larger than the cell: a triangle on a cell side marks both cells.
  const double half = 0.5 * cell * (1 + 1e-9);
  for (const Triangle& t : soup.triangles) {
    const std::array<Vec3d, 3> corner{soup.positions[t[0]] - origin, soup.positions[t[1]] - origin,
                                      soup.positions[t[2]] - origin};
    CellIndex lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      lo[k] =
          static_cast<std::int64_t>(std::floor(std::min({corner[0][k], corner[1][k], corner[2][k]}) / cell));
      hi[k] =
          static_cast<std::int64_t>(std::floor(std::max({corner[0][k], corner[1][k], corner[2][k]}) / cell));
    }
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const Vec3d centre = (Vec3d(double(i), double(j), double(k)) + Vec3d::Constant(0.5)) * cell;
          if (triangle_meets_box(corner, centre, half)) cells.insert({i, j, k});
        }
  }
  return cells;
}

}  // namespace

TriangleSoup cell_solid(const TriangleSoup& soup, double cell) {
  if (soup.triangles.empty()) return {};
  const Vec3d origin = used_bounding_box(soup).min();
  const std::set<CellIndex> cells = cells_met(soup, origin, cell);
  TriangleSoup out;
  std::map<CellIndex, Index> corner_index;  // grid corners, welded
  const auto corner = [&](const CellIndex& c) {
    const auto [it, added] = corner_index.try_emplace(c, static_cast<Index>(out.positions.size()));
    if (added) out.positions.push_back(origin + Vec3d(double(c[0]), double(c[1]), double(c[2])) * cell);
    return it->second;
  };
  for (const CellIndex& c : cells)
    for (int a = 0; a < 3; ++a)
      for (int side : {-1, 1}) {
        CellIndex next = c;
        next[a] += side;
        if (cells.count(next)) continue;
        // The side's square, corners q00 q10 q11 q01 over axes b, c with e_b x e_c = e_a.
        const int b = (a + 1) % 3, d = (a + 2) % 3;
        CellIndex q00 = c;
        q00[a] += side > 0 ? 1 : 0;
        CellIndex q10 = q00, q11 = q00, q01 = q00;
        ++q10[b];
        ++q11[b];
        ++q11[d];
        ++q01[d];
        const Index i00 = corner(q00), i10 = corner(q10), i11 = corner(q11), i01 = corner(q01);
        if (side > 0) {
          out.triangles.push_back({i00, i10, i11});
          out.triangles.push_back({i00, i11, i01});
        } else {
          out.triangles.push_back({i00, i11, i10});
          out.triangles.push_back({i00, i01, i11});
        }
      }
  return out;
}

}  // namespace mr
