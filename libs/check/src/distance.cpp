// Sampled one-sided distance with CGAL's AABB tree (one translation unit).

#include <mr/check/distance.h>
#include <mr/spatial/aabb_tree.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

namespace mr::check {
namespace {

// Exact predicates: in plain doubles the closest point on a sliver 1e25 long was put on the
// wrong side of an edge (distances of 1e25 from points on it). The tree's sphere-box test then
// also goes exact now and then, a third of the time on small models.
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalTriangle = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<CgalTriangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 to_point(const Vec3d& p) { return {p.x(), p.y(), p.z()}; }

// Samples of each face in a run of their own: `first[f]` to `first[f + 1]`.
struct Samples {
  std::vector<Vec3d> points;
  std::vector<std::size_t> first;
};

// The Morton (Z-order) key of (u, v) in [0, 1]^2, 16 bits each.
std::uint32_t morton_key(double u, double v) {
  const auto spread = [](double t) {
    std::uint32_t x = static_cast<std::uint32_t>(std::clamp(t, 0.0, 1.0) * 65535.0);
    x = (x | (x << 8)) & 0x00FF00FFu;
    x = (x | (x << 4)) & 0x0F0F0F0Fu;
    x = (x | (x << 2)) & 0x33333333u;
    return (x | (x << 1)) & 0x55555555u;
  };
  return spread(u) | (spread(v) << 1);
}

Samples sample_points(const TriangleSoup& soup, const DistanceOptions& options) {
  const double diagonal = bounding_box_diagonal(soup);
  double total_area = 0;
  for (const Triangle& t : soup.triangles)
    total_area += 0.5 * (soup.positions[t[1]] - soup.positions[t[0]])
                            .cross(soup.positions[t[2]] - soup.positions[t[0]])
                            .norm();
  double density = diagonal > 0 ? options.density / (diagonal * diagonal) : 0;
  const double fixed = 6.0 * double(soup.triangles.size());
  if (fixed + density * total_area > double(options.max_samples))
    density = std::max(0.0, (double(options.max_samples) - fixed) / std::max(total_area, 1e-300));

  std::mt19937_64 rng(12345);  // fixed seed: the same samples every run
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Samples samples;
  std::vector<Vec3d>& points = samples.points;
  for (const Triangle& t : soup.triangles) {
    samples.first.push_back(points.size());
    const Vec3d &a = soup.positions[t[0]], &b = soup.positions[t[1]], &c = soup.positions[t[2]];
    for (const Vec3d& p : {a, b, c, Vec3d((a + b) / 2), Vec3d((b + c) / 2), Vec3d((c + a) / 2)})
      points.push_back(p);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double expected = density * area;
    auto count = static_cast<std::size_t>(expected);
    if (unit(rng) < expected - double(count)) ++count;
    std::vector<std::pair<std::uint32_t, Vec3d>> interior;
    interior.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      interior.emplace_back(morton_key(u, v), a + u * (b - a) + v * (c - a));
    }
    // Each query starts from the previous sample's closest point: in
    // Morton order that is nearby, and the tree is pruned at once (random
    // order made trimesh/soup's 100 large triangles take 30 s).
    std::stable_sort(interior.begin(), interior.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (const auto& [key, p] : interior) points.push_back(p);
  }
  samples.first.push_back(points.size());
  return samples;
}

// A face by its corners' coordinates: equal for the same triangle, however its corners are
// numbered or ordered.
using FaceKey = std::array<double, 9>;

FaceKey face_key(const TriangleSoup& soup, const Triangle& t) {
  return sorted_corner_coordinates({soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]});
}

}  // namespace

DistanceReport one_sided_distance(const TriangleSoup& from, const TriangleSoup& to,
                                  const DistanceOptions& options) {
  DistanceReport report;
  std::vector<CgalTriangle> triangles;
  std::vector<FaceKey> to_faces;
  for (const Triangle& t : to.triangles) {
    CgalTriangle tri(to_point(to.positions[t[0]]), to_point(to.positions[t[1]]),
                     to_point(to.positions[t[2]]));
    if (tri.is_degenerate()) continue;
    triangles.push_back(tri);
    to_faces.push_back(face_key(to, t));
  }
  std::sort(to_faces.begin(), to_faces.end());
  if (triangles.empty() || from.triangles.empty()) return report;
  Tree tree(triangles.begin(), triangles.end());
  // Built here, not lazily by the first query: a query reads the primitives before it takes the
  // lock under which the first one sorts them (a data race between the threads below).
  tree.build();
  tree.accelerate_distance_queries();
  const Samples samples = sample_points(from, options);
  std::vector<double> distances(samples.points.size());
  // Per face, each query starts from the closest point of the one before (nearby: the same
  // face), which prunes the tree at once; the distance found does not depend on the start.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, from.triangles.size()), [&](const auto& range) {
    for (std::size_t f = range.begin(); f < range.end(); ++f) {
      const std::size_t begin = samples.first[f], end = samples.first[f + 1];
      // A face of `to` itself (a kept input triangle): every sample is on it.
      if (std::binary_search(to_faces.begin(), to_faces.end(), face_key(from, from.triangles[f]))) {
        std::fill(distances.begin() + begin, distances.begin() + end, 0.0);
        continue;
      }
      auto hint = tree.closest_point_and_primitive(to_point(samples.points[begin]));
      for (std::size_t i = begin; i < end; ++i) {
        const K::Point_3 query = to_point(samples.points[i]);
        if (i > begin) hint = tree.closest_point_and_primitive(query, hint);
        distances[i] = std::sqrt(CGAL::squared_distance(query, hint.first));
      }
    }
  });
  report.samples = distances.size();
  double sum = 0;
  for (std::size_t i = 0; i < distances.size(); ++i) {
    if (distances[i] > report.max) {
      report.max = distances[i];
      report.farthest = samples.points[i];
    }
    sum += distances[i];
  }
  report.mean = sum / double(distances.size());
  return report;
}

bool lies_within(const TriangleSoup& from, const TriangleSoup& to, double distance,
                 const DistanceOptions& options) {
  if (from.triangles.empty()) return true;
  if (to.triangles.empty()) return false;
  // Long slivers and large patch faces: pieces keep the queries local.
  const spatial::AabbTree tree(to, {.cut_large_triangles = true});
  const Samples samples = sample_points(from, options);
  const double distance_sq = distance * distance;
  const auto face_within = [&](std::size_t f) {
    const std::array<Vec3d, 3> corners = from.corners(f);
    if (tree.one_triangle_near_all(corners, distance_sq)) return true;
    for (std::size_t i = samples.first[f]; i < samples.first[f + 1]; ++i)
      if (!tree.any_within(samples.points[i], distance)) return false;
    return true;
  };
  // Not a cancelled loop: every range is asked, so the answer never depends
  // on the threads' timing; a range stops at its first face outside.
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, from.triangles.size()), true,
      [&](const tbb::blocked_range<std::size_t>& range, bool within) {
        for (std::size_t f = range.begin(); within && f < range.end(); ++f) within = face_within(f);
        return within;
      },
      [](bool a, bool b) { return a && b; });
}

}  // namespace mr::check
