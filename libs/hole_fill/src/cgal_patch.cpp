// The only translation unit with CGAL's hole filling, refinement and
// fairing templates (compile time).
#include "patch.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/fair.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <iterator>

namespace mr::hole_fill::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

Point to_point(const Vec3d& p) { return Point(p.x(), p.y(), p.z()); }
Vec3d to_vec(const Point& p) { return Vec3d(p.x(), p.y(), p.z()); }

// What triangulate_hole_polyline writes: a face over loop indices.
struct LoopFace {
  LoopFace(int a, int b, int c) : corners{Index(a), Index(b), Index(c)} {}
  Triangle corners;
};

// A hole with islands: the constrained Delaunay triangulation of every
// loop in the hole's plane, faces kept where they are inside the outer loop
// and outside the islands (an odd number of loops crossed from outside).
// Nothing when loops cross or touch in the plane (the triangulation then
// has points of its own).
using CdtVertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using CdtFaceBase =
    CGAL::Constrained_triangulation_face_base_2<Kernel,
                                                CGAL::Triangulation_face_base_with_info_2<int, Kernel>>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<
    Kernel, CGAL::Triangulation_data_structure_2<CdtVertexBase, CdtFaceBase>, CGAL::Exact_predicates_tag>;

void mark_nesting(Cdt& cdt) {
  for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = -1;
  std::vector<Cdt::Face_handle> frontier{cdt.infinite_face()}, next;
  cdt.infinite_face()->info() = 0;
  for (int level = 0; !frontier.empty(); ++level) {
    // Flood the current level; faces across a constraint start the next one.
    while (!frontier.empty()) {
      Cdt::Face_handle f = frontier.back();
      frontier.pop_back();
      for (int i = 0; i < 3; ++i) {
        Cdt::Face_handle g = f->neighbor(i);
        if (g->info() != -1) continue;
        if (cdt.is_constrained({f, i})) {
          next.push_back(g);
        } else {
          g->info() = level;
          frontier.push_back(g);
        }
      }
    }
    for (Cdt::Face_handle g : next)
      if (g->info() == -1) g->info() = level + 1, frontier.push_back(g);
    next.clear();
  }
}

std::vector<Triangle> triangulate_with_islands(const HoleNeighbourhood& hole) {
  Cdt cdt;
  std::size_t first = 0;
  std::vector<std::size_t> sizes{hole.loop_size};
  sizes.insert(sizes.end(), hole.island_sizes.begin(), hole.island_sizes.end());
  for (std::size_t size : sizes) {
    std::vector<Cdt::Vertex_handle> loop;
    for (std::size_t i = first; i < first + size; ++i) {
      loop.push_back(cdt.insert(Kernel::Point_2(hole.projected[i].x(), hole.projected[i].y())));
      loop.back()->info() = Index(i);
    }
    for (std::size_t i = 0; i < size; ++i) cdt.insert_constraint(loop[i], loop[(i + 1) % size]);
    first += size;
  }
  // Loops crossing in the plane add points, coinciding ones merge: either way the count differs.
  if (cdt.number_of_vertices() != first) return {};
  mark_nesting(cdt);
  std::vector<Triangle> faces;
  for (Cdt::Face_handle f : cdt.finite_face_handles())
    if (f->info() % 2 == 1)
      faces.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  return faces;
}

std::optional<Mesh> as_mesh(const HoleNeighbourhood& hole, const std::vector<Triangle>& patch);

// The named parameters of CGAL's hole triangulation for `triangulator`.
auto triangulation_parameters(const HoleNeighbourhood& hole, Triangulator triangulator) {
  return CGAL::parameters::use_delaunay_triangulation(triangulator != Triangulator::full_search)
      .use_2d_constrained_delaunay_triangulation(triangulator == Triangulator::plane_2d)
      .do_not_use_cubic_algorithm(triangulator != Triangulator::full_search &&
                                  hole.loop_size > kCubicSearchMaxLoop);
}

// The loop triangulated as a hole of the ring's mesh, so that no diagonal
// repeats an edge the surface already has (CGAL checks the mesh's edges);
// nothing when the ring is not a valid polygon mesh or the loop's first
// edge is not on its border.
std::optional<std::vector<Triangle>> triangulate_in_ring(const HoleNeighbourhood& hole,
                                                         Triangulator triangulator) {
  std::optional<Mesh> ring = as_mesh(hole, {});
  if (!ring) return std::nullopt;
  const auto h = CGAL::halfedge(Mesh::Vertex_index(0), Mesh::Vertex_index(1), *ring);
  if (!h.second || !ring->is_border(h.first)) return std::nullopt;
  std::vector<Mesh::Face_index> added;
  PMP::triangulate_hole(*ring, h.first, std::back_inserter(added),
                        triangulation_parameters(hole, triangulator));
  std::vector<Triangle> faces;
  for (Mesh::Face_index f : added) {
    Triangle t{};
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(ring->halfedge(f), *ring))
      t[k++] = Index(std::size_t(v));
    faces.push_back(t);
  }
  return faces;
}

std::vector<Triangle> triangulate_loop(const HoleNeighbourhood& hole, Triangulator triangulator) {
  if (std::optional<std::vector<Triangle>> in_ring = triangulate_in_ring(hole, triangulator);
      in_ring && !in_ring->empty())
    return *in_ring;
  std::vector<Point> points, third;
  for (std::size_t i = 0; i < hole.loop_size; ++i) {
    points.push_back(to_point(hole.positions[i]));
    third.push_back(to_point(hole.opposite[i]));
  }
  std::vector<LoopFace> faces;
  PMP::triangulate_hole_polyline(points, third, std::back_inserter(faces),
                                 triangulation_parameters(hole, triangulator));
  std::vector<Triangle> out;
  for (const LoopFace& f : faces) out.push_back(f.corners);
  return out;
}

// Orients the triangulation so that loop edge 0 -> 1 runs forward in the
// face that holds it (the faces of a disk are oriented alike).
void orient_along_loop(std::vector<Triangle>& faces) {
  for (const Triangle& f : faces)
    for (int i = 0; i < 3; ++i) {
      if (f[i] == 0 && f[(i + 1) % 3] == 1) return;
      if (f[i] == 1 && f[(i + 1) % 3] == 0) {
        for (Triangle& g : faces) std::swap(g[1], g[2]);
        return;
      }
    }
}

// The ring and the patch as one CGAL mesh, vertex i being position i and
// face j being face j of ring + patch; nothing when that is not a valid
// polygon mesh (a ring that pinches).
std::optional<Mesh> as_mesh(const HoleNeighbourhood& hole, const std::vector<Triangle>& patch) {
  std::vector<Point> points;
  for (const Vec3d& p : hole.positions) points.push_back(to_point(p));
  std::vector<std::array<std::size_t, 3>> polygons;
  for (const auto* faces : {&hole.ring, &patch})
    for (const Triangle& t : *faces) polygons.push_back({t[0], t[1], t[2]});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return std::nullopt;
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (mesh.number_of_vertices() != points.size() || mesh.number_of_faces() != polygons.size())
    return std::nullopt;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (mesh.point(Mesh::Vertex_index(Index(i))) != points[i]) return std::nullopt;
  return mesh;
}

// Refines the patch faces (the faces after the ring) to the density of the
// faces around them and fairs the vertices it adds; false if fairing fails.
bool refine_and_fair(Mesh& mesh, std::size_t ring_faces, Fairing fairing) {
  std::vector<Mesh::Face_index> patch;
  for (Mesh::Face_index f : mesh.faces())
    if (std::size_t(f) >= ring_faces) patch.push_back(f);
  std::vector<Mesh::Vertex_index> added;
  std::vector<Mesh::Face_index> new_faces;
  PMP::refine(mesh, patch, std::back_inserter(new_faces), std::back_inserter(added),
              CGAL::parameters::density_control_factor(std::sqrt(2.0)));
  if (added.empty() || fairing == Fairing::none) return true;
  return PMP::fair(mesh, added, CGAL::parameters::fairing_continuity(int(fairing)));
}

// The patch faces of `mesh` (every face after the ring) in local indices,
// or nothing if refinement touched a ring face.
std::optional<Patch> extract_patch(const Mesh& mesh, const HoleNeighbourhood& hole) {
  Patch patch;
  for (Mesh::Face_index f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      t[k++] = Index(std::size_t(v));
    if (std::size_t(f) < hole.ring.size()) {
      const Triangle& r = hole.ring[std::size_t(f)];
      if (std::is_permutation(t.begin(), t.end(), r.begin())) continue;
      return std::nullopt;
    }
    patch.faces.push_back(t);
  }
  for (std::size_t v = hole.positions.size(); v < mesh.number_of_vertices(); ++v)
    patch.new_positions.push_back(to_vec(mesh.point(Mesh::Vertex_index(Index(v)))));
  return patch;
}

}  // namespace

std::optional<Patch> make_patch(const HoleNeighbourhood& hole, const PatchMethod& method) {
  std::vector<Triangle> faces = hole.island_sizes.empty() ? triangulate_loop(hole, method.triangulator)
                                                          : triangulate_with_islands(hole);
  if (faces.empty()) return std::nullopt;
  orient_along_loop(faces);
  if (!method.refine) return Patch{{}, std::move(faces)};
  HoleNeighbourhood local = hole;
  std::optional<Mesh> mesh = as_mesh(local, faces);
  if (!mesh) {  // a pinched ring: refine and fair the patch alone, its border held fixed
    local.ring.clear();
    mesh = as_mesh(local, faces);
    if (!mesh) return std::nullopt;
  }
  if (!refine_and_fair(*mesh, local.ring.size(), method.fairing) || mesh->has_garbage()) return std::nullopt;
  return extract_patch(*mesh, local);
}

}  // namespace mr::hole_fill::detail
