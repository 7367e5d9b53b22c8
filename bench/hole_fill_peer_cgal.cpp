// The peer of hole-fill in bench/hole_fill_bench.py: CGAL's hole filling as a
// CGAL user writes it, after the documented example (hole_filling_example_SM.cpp):
// the soup is oriented and made a Surface_mesh, and every boundary cycle is
// closed by triangulate_refine_and_fair_hole with default parameters.
// Usage: hole_fill_peer_cgal IN OUT
// Prints {"holes": N, "filled": K, "seconds": S}: K holes whose fairing
// succeeded, S the seconds spent filling. Exit 2 on unreadable input.

#include <mr/core/weld.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <iterator>
#include <tuple>
#include <vector>

namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Mesh to_mesh(const mr::TriangleSoup& soup) {
  std::vector<Point> points;
  points.reserve(soup.positions.size());
  for (const mr::Vec3d& p : soup.positions) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(soup.triangles.size());
  for (const mr::Triangle& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  PMP::orient_polygon_soup(points, polygons);  // duplicates non-manifold vertices
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return mesh;
}

mr::TriangleSoup to_soup(Mesh& mesh) {
  mesh.collect_garbage();
  mr::TriangleSoup soup;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Point& p = mesh.point(v);
    soup.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (Mesh::Face_index f : mesh.faces()) {
    mr::Triangle t{};
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      if (k < 3) t[k++] = mr::Index(std::size_t(v));
    soup.triangles.push_back(t);
  }
  return soup;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: hole_fill_peer_cgal IN OUT\n");
    return 2;
  }
  const mr::io::Registry registry = mr::io::make_default_registry();
  Mesh mesh;
  try {
    mesh = to_mesh(mr::weld_identical_vertices(mr::io::read_surface(registry, argv[1])));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hole_fill_peer_cgal: %s\n", e.what());  // names the file
    return 2;
  }

  const auto start = std::chrono::steady_clock::now();
  std::vector<Mesh::Halfedge_index> holes;  // one border halfedge per hole
  PMP::extract_boundary_cycles(mesh, std::back_inserter(holes));
  int filled = 0;
  for (Mesh::Halfedge_index h : holes) {
    std::vector<Mesh::Face_index> faces;
    std::vector<Mesh::Vertex_index> vertices;
    const bool faired = std::get<0>(PMP::triangulate_refine_and_fair_hole(mesh, h, std::back_inserter(faces),
                                                                          std::back_inserter(vertices)));
    filled += faired ? 1 : 0;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  try {
    mr::io::write_surface(registry, to_soup(mesh), argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hole_fill_peer_cgal: %s\n", e.what());
    return 1;
  }
  std::printf("{\"holes\": %zu, \"filled\": %d, \"seconds\": %.6f}\n", holes.size(), filled, seconds);
  return 0;
}
