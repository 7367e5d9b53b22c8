#include "islands.h"

#include <mr/core/union_find.h>
#include <mr/kernel/predicates.h>

#include <cmath>

namespace mr::hole_fill::detail {
namespace {

using Vec2d = Eigen::Vector2d;

std::vector<std::size_t> face_components_of_vertices(const TriangleSoup& soup) {
  UnionFind parts(soup.positions.size());
  for (const Triangle& t : soup.triangles) parts.unite(t[0], t[1]), parts.unite(t[1], t[2]);
  std::vector<std::size_t> part(soup.positions.size());
  for (std::size_t v = 0; v < part.size(); ++v) part[v] = parts.find(v);
  return part;
}

std::vector<Vec2d> projected(const TriangleSoup& soup, const BorderLoop& loop, const HolePlane& plane) {
  std::vector<Vec2d> out;
  for (Index v : loop.vertices) out.push_back(plane.project(soup.positions[v]));
  return out;
}

// Winding number of a closed polygon around q, from exact orientations.
int winding(const std::vector<Vec2d>& polygon, const Vec2d& q) {
  int w = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2d &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    if (a.y() <= q.y()) {
      if (b.y() > q.y() && orient2d(a, b, q) > 0) ++w;
    } else if (b.y() <= q.y() && orient2d(a, b, q) < 0) {
      --w;
    }
  }
  return w;
}

double signed_area(const std::vector<Vec2d>& polygon) {
  double area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2d &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  return area / 2.0;
}

struct LoopShape {
  HolePlane plane;
  std::vector<Vec2d> polygon;
  double extent = 0.0;
};

bool is_island_of(const TriangleSoup& soup, const std::vector<Index>& part_vertices, const BorderLoop& island,
                  const LoopShape& outer) {
  if (signed_area(projected(soup, island, outer.plane)) >= 0.0) return false;  // must turn the other way
  const Vec3d normal = outer.plane.u.cross(outer.plane.v);
  for (Index v : part_vertices) {
    const Vec3d& p = soup.positions[v];
    if (std::abs((p - outer.plane.origin).dot(normal)) > outer.extent) return false;
    if (winding(outer.polygon, outer.plane.project(p)) != 1) return false;
  }
  return true;
}

}  // namespace

HolePlane hole_plane(const TriangleSoup& welded, const BorderLoop& loop) {
  Vec3d normal = Vec3d::Zero(), centroid = Vec3d::Zero();
  const std::size_t n = loop.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d &a = welded.positions[loop.vertices[i]], &b = welded.positions[loop.vertices[(i + 1) % n]];
    normal += a.cross(b);  // Newell: twice the vector area of the loop
    centroid += a;
  }
  centroid /= double(n);
  if (normal.norm() == 0.0) normal = Vec3d::UnitZ();
  normal.normalize();
  const Vec3d u = normal.unitOrthogonal();
  return {centroid, u, normal.cross(u)};
}

std::vector<Hole> group_islands(const TriangleSoup& welded, std::vector<BorderLoop> loops) {
  const std::vector<std::size_t> part = face_components_of_vertices(welded);
  std::vector<std::size_t> loops_in_part(welded.positions.size(), 0);
  for (const BorderLoop& l : loops) ++loops_in_part[part[l.vertices.front()]];
  std::vector<std::vector<Index>> part_vertices(welded.positions.size());
  for (Index v = 0; v < welded.positions.size(); ++v) part_vertices[part[v]].push_back(v);

  std::vector<LoopShape> shapes;
  for (const BorderLoop& l : loops) {
    LoopShape s;
    s.plane = hole_plane(welded, l);
    s.polygon = projected(welded, l, s.plane);
    Vec3d lo = welded.positions[l.vertices.front()], hi = lo;
    for (Index v : l.vertices) lo = lo.cwiseMin(welded.positions[v]), hi = hi.cwiseMax(welded.positions[v]);
    s.extent = (hi - lo).norm();
    shapes.push_back(std::move(s));
  }
  std::vector<int> island_of(loops.size(), -1);
  for (std::size_t b = 0; b < loops.size(); ++b) {
    const std::size_t pb = part[loops[b].vertices.front()];
    if (loops_in_part[pb] != 1) continue;
    for (std::size_t a = 0; a < loops.size() && island_of[b] < 0; ++a)
      if (a != b && island_of[a] < 0 && part[loops[a].vertices.front()] != pb &&
          is_island_of(welded, part_vertices[pb], loops[b], shapes[a]))
        island_of[b] = int(a);
  }
  std::vector<Hole> holes(loops.size());
  for (std::size_t b = 0; b < loops.size(); ++b)
    if (island_of[b] >= 0) holes[std::size_t(island_of[b])].islands.push_back(std::move(loops[b]));
  std::vector<Hole> out;
  for (std::size_t a = 0; a < loops.size(); ++a) {
    if (island_of[a] >= 0) continue;
    holes[a].outer = std::move(loops[a]);
    out.push_back(std::move(holes[a]));
  }
  return out;
}

}  // namespace mr::hole_fill::detail
