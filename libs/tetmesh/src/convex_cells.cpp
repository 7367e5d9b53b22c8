#include "convex_cells.h"

#include <mr/core/errors.h>

#include <algorithm>

namespace mr::tetmesh::detail {
namespace {

// The cycle starting at its smallest vertex, going towards the smaller of
// that vertex's two neighbours; `reversed` tells whether this flipped the
// orientation of the input cycle.
// A polygon vertex with the bit set of the polygon sides it lies on.
struct PolygonVertex {
  Index id;
  std::uint32_t sides;
};

// The cycle starting at its smallest vertex, going towards the smaller of
// that vertex's two neighbours; `reversed` tells whether this flipped the
// orientation of the input cycle.
std::vector<PolygonVertex> canonical_cycle(std::span<const Index> cycle, std::span<const std::uint32_t> sides,
                                           bool& reversed) {
  const std::size_t n = cycle.size();
  const std::size_t start =
      static_cast<std::size_t>(std::min_element(cycle.begin(), cycle.end()) - cycle.begin());
  const Index next = cycle[(start + 1) % n];
  const Index previous = cycle[(start + n - 1) % n];
  reversed = previous < next;
  std::vector<PolygonVertex> result(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t at = reversed ? (start + n - i) % n : (start + i) % n;
    result[i] = {cycle[at], sides.empty() ? 0u : sides[at]};
  }
  return result;
}

// Collinearity of three vertices of a convex polygon: sharing a side proves
// it without arithmetic (these exact zeros are the costly evaluations).
bool on_a_line(const Mesh& mesh, const PolygonVertex& a, const PolygonVertex& b, const PolygonVertex& c) {
  if ((a.sides & b.sides & c.sides) != 0) return true;
  return collinear(mesh.position(a.id), mesh.position(b.id), mesh.position(c.id));
}

// Whether cutting off the corner at `ear` leaves a polygon with area. It
// does not when every other corner lies on the line of the ear's diagonal:
// the polygon was a triangle whose opposite side holds flat points.
bool leaves_area(const Mesh& mesh, const std::vector<PolygonVertex>& polygon, std::size_t ear) {
  const std::size_t n = polygon.size();
  const PolygonVertex& a = polygon[(ear + n - 1) % n];
  const PolygonVertex& b = polygon[(ear + 1) % n];
  for (std::size_t k = 2; k + 1 < n; ++k) {
    if (!on_a_line(mesh, a, b, polygon[(ear + k) % n])) return true;
  }
  return false;
}

}  // namespace

bool sees_all(const Mesh& mesh, const HybridPoint& apex, Index apex_id,
              std::span<const CellTriangle> boundary) {
  std::uint64_t planes_through_apex = 0;  // planes 0..63 of triangles having the apex
  for (const CellTriangle& triangle : boundary) {
    const auto& c = triangle.corners;
    const bool has_apex = c[0] == apex_id || c[1] == apex_id || c[2] == apex_id;
    if (has_apex && triangle.plane >= 0 && triangle.plane < 64) planes_through_apex |= 1ull << triangle.plane;
  }
  for (const CellTriangle& triangle : boundary) {
    const auto& c = triangle.corners;
    if (c[0] == apex_id || c[1] == apex_id || c[2] == apex_id) continue;
    if (triangle.plane >= 0 && triangle.plane < 64 && ((planes_through_apex >> triangle.plane) & 1) != 0) {
      return false;  // coplanar with the apex: a flat cone tet
    }
    if (orient3d(apex, mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2])) <= 0) {
      return false;
    }
  }
  return true;
}

namespace {

bool same_corners(std::array<Index, 3> a, std::array<Index, 3> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  return a == b;
}

// Boundary triangles through the apex are not coned over: they are side
// faces of the cone tets, which must carry their marks.
void mark_side_face(const CellTriangle& triangle, std::span<ConeTet> tets) {
  for (ConeTet& tet : tets) {
    for (int k = 1; k < 4; ++k) {
      const Tet& c = tet.corners;
      const std::array<Index, 3> face{c[0], c[k == 1 ? 2 : 1], c[k == 3 ? 2 : 3]};
      if (same_corners(face, triangle.corners)) {
        tet.face_ids[k] = triangle.ids;
        return;
      }
    }
  }
  throw RunError("triangle insertion: a tracked face of a cell is missing from its cone (internal error)");
}

}  // namespace

void cone(Index apex, std::span<const CellTriangle> boundary, std::vector<ConeTet>& out) {
  const std::size_t first = out.size();
  for (const CellTriangle& triangle : boundary) {
    const auto& c = triangle.corners;
    if (c[0] == apex || c[1] == apex || c[2] == apex) continue;
    out.push_back({Tet{apex, c[0], c[1], c[2]}, {triangle.ids, nullptr, nullptr, nullptr}});
  }
  const std::span<ConeTet> made(out.data() + first, out.size() - first);
  for (const CellTriangle& triangle : boundary) {
    const auto& c = triangle.corners;
    const bool through_apex = c[0] == apex || c[1] == apex || c[2] == apex;
    if (through_apex && triangle.ids != nullptr) mark_side_face(triangle, made);
  }
}

namespace {

std::vector<Index> cell_vertices(std::span<const CellTriangle> boundary) {
  std::vector<Index> vertices;
  vertices.reserve(boundary.size() * 3);
  for (const CellTriangle& triangle : boundary) {
    vertices.insert(vertices.end(), triangle.corners.begin(), triangle.corners.end());
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

// The average of the corners: strictly inside a convex cell. The double
// average is tried first; the exact one is used when rounding put the
// double one outside (thin cells).
HybridPoint interior_point(const Mesh& mesh, std::span<const Index> vertices,
                           std::span<const CellTriangle> boundary) {
  Vec3d sum = Vec3d::Zero();
  for (Index v : vertices) sum += mesh.position(v).approx;
  const HybridPoint approx(sum / static_cast<double>(vertices.size()));
  if (sees_all(mesh, approx, kNoVertex, boundary)) return approx;
  ExactPoint3 exact(mpq_class(0), mpq_class(0), mpq_class(0));
  for (Index v : vertices) {
    const ExactPoint3 p = mesh.position(v).to_exact();
    exact.x += p.x;
    exact.y += p.y;
    exact.z += p.z;
  }
  const mpq_class count(static_cast<long>(vertices.size()));
  exact.x /= count;
  exact.y /= count;
  exact.z /= count;
  return HybridPoint::from_exact(std::move(exact));
}

}  // namespace

bool collinear(const HybridPoint& p, const HybridPoint& q, const HybridPoint& r) {
  for (int axis = 0; axis < 3; ++axis) {
    if (orient2d_projected(p, q, r, axis) != 0) return false;
  }
  return true;
}

void triangulate_convex_polygon(const Mesh& mesh, std::span<const Index> cycle,
                                std::span<const std::uint32_t> sides,
                                std::vector<std::array<Index, 3>>& out) {
  bool reversed = false;
  std::vector<PolygonVertex> polygon = canonical_cycle(cycle, sides, reversed);
  const auto emit = [&](const PolygonVertex& a, const PolygonVertex& b, const PolygonVertex& c) {
    out.push_back(reversed ? std::array<Index, 3>{a.id, c.id, b.id} : std::array<Index, 3>{a.id, b.id, c.id});
  };
  // Ear clipping: every strict corner of a convex polygon is an ear. Clipping
  // the first one after the start gives a fan from the start when there are
  // no flat points, and stays canonical when there are.
  while (polygon.size() > 3) {
    const std::size_t n = polygon.size();
    std::size_t ear = n;
    for (std::size_t i = 1; i <= n; ++i) {
      const std::size_t at = i % n;
      if (!on_a_line(mesh, polygon[(at + n - 1) % n], polygon[at], polygon[(at + 1) % n]) &&
          leaves_area(mesh, polygon, at)) {
        ear = at;
        break;
      }
    }
    if (ear == n) throw RunError("triangle insertion: a polygon of a cut has all its corners on a line");
    emit(polygon[(ear + n - 1) % n], polygon[ear], polygon[(ear + 1) % n]);
    polygon.erase(polygon.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  if (on_a_line(mesh, polygon[0], polygon[1], polygon[2])) {
    throw RunError("triangle insertion: a polygon of a cut is degenerate");
  }
  emit(polygon[0], polygon[1], polygon[2]);
}

void tetrahedralize_convex_cell(Mesh& mesh, std::span<const CellTriangle> boundary, std::vector<ConeTet>& out,
                                Index& steiner) {
  steiner = kNoVertex;
  const std::vector<Index> vertices = cell_vertices(boundary);
  for (Index v : vertices) {
    if (sees_all(mesh, mesh.position(v), v, boundary)) {
      cone(v, boundary, out);
      return;
    }
  }
  const HybridPoint inside = interior_point(mesh, vertices, boundary);
  if (!sees_all(mesh, inside, kNoVertex, boundary)) {
    throw RunError("triangle insertion: a cut cell is not convex (internal error)");
  }
  steiner = mesh.add_vertex(inside);
  cone(steiner, boundary, out);
}

}  // namespace mr::tetmesh::detail
