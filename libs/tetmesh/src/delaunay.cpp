// CGAL's Delaunay_triangulation_3 on Epick (exact predicates): the only file
// of mr_tetmesh that includes CGAL. Insertion of a range sorts the points
// spatially (CGAL's spatial_sort with its own fixed-seed shuffle); the
// resulting triangulation does not depend on the order anyway, since CGAL
// breaks co-spherical ties by symbolic perturbation, so the parallel
// insertion gives the same tets (in another order, which the caller fixes).

#include "delaunay.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <tbb/task_arena.h>

#include <utility>

namespace mr::tetmesh::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<Index, K>;
using CellBase = CGAL::Delaunay_triangulation_cell_base_3<K>;

template <class Concurrency>
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase, Concurrency>;

using SequentialDelaunay = CGAL::Delaunay_triangulation_3<K, Tds<CGAL::Sequential_tag>>;

std::vector<std::pair<K::Point_3, Index>> with_indices(std::span<const Vec3d> points) {
  std::vector<std::pair<K::Point_3, Index>> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    out.emplace_back(K::Point_3(points[i].x(), points[i].y(), points[i].z()), static_cast<Index>(i));
  }
  return out;
}

template <class Triangulation>
std::vector<Tet> finite_tets(const Triangulation& dt) {
  std::vector<Tet> tets;
  tets.reserve(dt.number_of_finite_cells());
  for (auto cell = dt.finite_cells_begin(); cell != dt.finite_cells_end(); ++cell) {
    tets.push_back(
        {cell->vertex(0)->info(), cell->vertex(1)->info(), cell->vertex(2)->info(), cell->vertex(3)->info()});
  }
  return tets;
}

std::vector<Tet> sequential_delaunay(std::span<const Vec3d> points) {
  const auto pairs = with_indices(points);
  SequentialDelaunay dt(pairs.begin(), pairs.end());
  return finite_tets(dt);
}

#ifdef CGAL_LINKED_WITH_TBB
using ParallelDelaunay =
    CGAL::Delaunay_triangulation_3<K, Tds<CGAL::Parallel_tag>, CGAL::Default,
                                   CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking>>;

std::vector<Tet> parallel_delaunay(std::span<const Vec3d> points, const Vec3d& box_min, const Vec3d& box_max,
                                   int threads) {
  const auto pairs = with_indices(points);
  const CGAL::Bbox_3 box(box_min.x(), box_min.y(), box_min.z(), box_max.x(), box_max.y(), box_max.z());
  ParallelDelaunay::Lock_data_structure locks(box, 50);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  std::vector<Tet> tets;
  arena.execute([&] {
    ParallelDelaunay dt(K(), &locks);
    dt.insert(pairs.begin(), pairs.end());
    tets = finite_tets(dt);
  });
  return tets;
}
#endif

}  // namespace

std::vector<Tet> delaunay_tets(std::span<const Vec3d> points, [[maybe_unused]] const Vec3d& box_min,
                               [[maybe_unused]] const Vec3d& box_max, bool parallel,
                               [[maybe_unused]] int threads) {
#ifdef CGAL_LINKED_WITH_TBB
  if (parallel && threads != 1) return parallel_delaunay(points, box_min, box_max, threads);
#endif
  (void)parallel;
  return sequential_delaunay(points);
}

}  // namespace mr::tetmesh::detail
