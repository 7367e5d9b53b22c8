// Outer hull: OpenVDB's unsigned distance band around the soup, its walls
// (voxels near a triangle), a flood fill of the outside through the rest,
// and the level set at the wall radius between outside and inside, meshed.
// Reachability decides most voxels: the soups that reach this fallback
// (crumpled, crossing thousands of times) have a winding number that is
// noise near the surface. Away from it, in the pockets the walls enclose,
// it still tells a solid's inside from a hollow one's cavity, so each
// pocket asks it a few times.

#include <mr/core/errors.h>
#include <mr/volume/outer_hull.h>
#include <mr/winding_number/winding_number.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mr::volume {
namespace {

using openvdb::Coord;
using openvdb::FloatGrid;

// Half width of the distance band, in voxels: beyond the wall radius by two
// voxels, so that the level set has active voxels on both sides.
constexpr double kBandBeyondWall = 2.0;

enum Voxel : std::uint8_t { kFree = 0, kWall = 1, kOutside = 2, kInside = 3 };

// Winding-number samples per enclosed pocket; the majority decides.
constexpr std::size_t kPocketSamples = 7;
// Pockets of fewer voxels are inside whatever the winding number says:
// folds of a crumpled surface, not a solid's cavity (one that small is
// below what the grid resolves).
constexpr std::size_t kSmallestCavity = 64;

/// The band's voxels and a margin of one free voxel around them, densely.
class DenseBox {
 public:
  explicit DenseBox(const openvdb::CoordBBox& active)
      : lo_(active.min().offsetBy(-1)), dims_(active.dim().offsetBy(2)) {}
  std::size_t size() const {
    return std::size_t(dims_.x()) * std::size_t(dims_.y()) * std::size_t(dims_.z());
  }
  Coord coord(std::size_t index) const {
    const std::size_t nz = std::size_t(dims_.z()), ny = std::size_t(dims_.y());
    return lo_.offsetBy(int(index / (ny * nz)), int((index / nz) % ny), int(index % nz));
  }
  std::size_t index(const Coord& ijk) const {
    const Coord d = ijk - lo_;
    return (std::size_t(d.x()) * std::size_t(dims_.y()) + std::size_t(d.y())) * std::size_t(dims_.z()) +
           std::size_t(d.z());
  }
  /// The six face neighbours of `index` inside the box, through `visit`.
  template <class Visit>
  void for_each_neighbour(std::size_t index, Visit&& visit) const {
    const std::size_t nz = std::size_t(dims_.z()), nyz = std::size_t(dims_.y()) * nz;
    const std::size_t x = index / nyz, y = (index / nz) % std::size_t(dims_.y()), z = index % nz;
    if (x > 0) visit(index - nyz);
    if (x + 1 < std::size_t(dims_.x())) visit(index + nyz);
    if (y > 0) visit(index - nz);
    if (y + 1 < std::size_t(dims_.y())) visit(index + nz);
    if (z > 0) visit(index - 1);
    if (z + 1 < nz) visit(index + 1);
  }

 private:
  Coord lo_;
  Coord dims_;
};

// The box's voxels, known before the band is made: the soup's box grown
// by the band and the margin on each side.
void check_grid_fits(const TriangleSoup& soup, double voxel_size, double half_width, std::size_t max_voxels) {
  const Vec3d cells =
      used_bounding_box(soup).sizes() / voxel_size + Vec3d::Constant(2.0 * (half_width + 2.0));
  const double count = cells.prod();
  if (!(count <= double(max_voxels)))
    throw RunError("the outer hull would need about " + std::to_string(static_cast<long long>(count)) +
                   " voxels, more than " + std::to_string(max_voxels));
}

// Positions relative to `origin` (the soup's box corner): float keeps
// them to a few parts in 10^7 of the soup's size wherever it lies.
FloatGrid::Ptr distance_band(const TriangleSoup& soup, const Vec3d& origin,
                             const openvdb::math::Transform& xform, double half_width) {
  std::vector<openvdb::Vec3s> points;
  points.reserve(soup.positions.size());
  for (const Vec3d& p : soup.positions) {
    const Vec3d q = p - origin;
    points.emplace_back(float(q.x()), float(q.y()), float(q.z()));
  }
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  return openvdb::tools::meshToUnsignedDistanceField<FloatGrid>(xform, points, triangles, {},
                                                                static_cast<float>(half_width));
}

struct Pocket {
  std::size_t voxels = 0;
  /// The voxels reached 1, 2, 4, 8, ... voxels in, the last kPocketSamples
  /// of them: spread from the pocket's rim to its depth.
  std::vector<std::size_t> samples;
};

// Gives `to` to the voxels in state `from` connected to `seed` (in that
// state itself), one breadth-first layer at a time.
Pocket grow(std::vector<std::uint8_t>& state, const DenseBox& box, std::size_t seed, std::uint8_t from,
            std::uint8_t to) {
  std::vector<std::size_t> layer{seed}, next, samples;
  std::size_t reached = 0;
  state[seed] = to;
  while (!layer.empty()) {
    next.clear();
    for (const std::size_t v : layer) {
      ++reached;
      if ((reached & (reached - 1)) == 0) samples.push_back(v);
      box.for_each_neighbour(v, [&](std::size_t n) {
        if (state[n] != from) return;
        state[n] = to;
        next.push_back(n);
      });
    }
    layer.swap(next);
  }
  if (samples.size() > kPocketSamples) samples.erase(samples.begin(), samples.end() - kPocketSamples);
  return {reached, std::move(samples)};
}

// A pocket is inside where most of its samples have |winding number| > 1/2
// (|w|: a soup oriented inward throughout is a solid too).
bool pocket_is_inside(const Pocket& pocket, const DenseBox& box, const FloatGrid& band,
                      const WindingNumberTree& winding, const Vec3d& origin) {
  if (pocket.voxels < kSmallestCavity) return true;
  const std::vector<std::size_t>& samples = pocket.samples;
  std::vector<Vec3d> queries;
  for (const std::size_t v : samples) {
    const openvdb::Vec3d p = band.transform().indexToWorld(box.coord(v));
    queries.push_back(origin + Vec3d(p.x(), p.y(), p.z()));
  }
  std::size_t inside = 0;
  for (const double w : winding.evaluate(queries)) inside += std::abs(w) > 0.5;
  return 2 * inside > samples.size();
}

// Walls; then the outside, grown from the box's corner (in the margin, so
// free); then each pocket left, inside or outside by its winding number.
std::vector<std::uint8_t> classify(const FloatGrid& band, const DenseBox& box, float wall,
                                   const WindingNumberTree& winding, const Vec3d& origin) {
  std::vector<std::uint8_t> state(box.size(), kFree);
  for (auto it = band.cbeginValueOn(); it; ++it)
    if (*it < wall) state[box.index(it.getCoord())] = kWall;
  grow(state, box, 0, kFree, kOutside);
  for (std::size_t v = 0; v < state.size(); ++v) {
    if (state[v] != kFree) continue;
    if (!pocket_is_inside(grow(state, box, v, kFree, kInside), box, band, winding, origin))
      grow(state, box, v, kInside, kOutside);
  }
  return state;
}

// Positive outside, negative in walls and inside, zero at the wall radius
// from the soup on the outside. Voxels beyond the band are inactive; the
// flood fill gives them the sign of the band around them.
FloatGrid::Ptr hull_level_set(const FloatGrid& band, const DenseBox& box,
                              const std::vector<std::uint8_t>& state, float wall, float voxel) {
  const float background = static_cast<float>(band.background());
  FloatGrid::Ptr level_set = FloatGrid::create(background);
  level_set->setTransform(band.transform().copy());
  level_set->setGridClass(openvdb::GRID_LEVEL_SET);
  auto accessor = level_set->getAccessor();
  const float inside_floor = -0.01f * voxel;  // inside voxels stay strictly inside
  for (auto it = band.cbeginValueOn(); it; ++it) {
    const float distance = *it;
    const std::uint8_t s = state[box.index(it.getCoord())];
    const float value = s == kInside ? std::min(wall - distance, inside_floor) : distance - wall;
    accessor.setValue(it.getCoord(), value);
  }
  openvdb::tools::signedFloodFill(level_set->tree());
  return level_set;
}

struct Polygons {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
};

Polygons mesh_level(const FloatGrid& grid, double isovalue, double adaptivity) {
  Polygons mesh;
  openvdb::tools::volumeToMesh(grid, mesh.points, mesh.triangles, mesh.quads, isovalue, adaptivity);
  return mesh;
}

// The walls closed the solid a wall radius out; the signed distance to its
// surface lets that surface move back toward the soup (a closing). The
// distance is to the meshed surface, the sign the level set's: OpenVDB's
// own rebuild signs by reachability from outside and would fill cavities.
FloatGrid::Ptr signed_distance_to(const Polygons& surface, const FloatGrid& level_set, double half_width) {
  FloatGrid::Ptr distance = openvdb::tools::meshToUnsignedDistanceField<FloatGrid>(
      level_set.transform(), surface.points, surface.triangles, surface.quads,
      static_cast<float>(half_width));
  const auto sign = level_set.getConstAccessor();
  for (auto it = distance->beginValueOn(); it; ++it)
    if (sign.getValue(it.getCoord()) < 0.0f) it.setValue(-*it);
  distance->setGridClass(openvdb::GRID_LEVEL_SET);
  openvdb::tools::signedFloodFill(distance->tree());
  return distance;
}

// volumeToMesh winds polygons clockwise seen from outside; the soup's
// triangles turn counter-clockwise. Quads split along the shorter diagonal.
TriangleSoup to_soup(const Polygons& mesh, const Vec3d& origin) {
  const auto& [points, triangles, quads] = mesh;
  TriangleSoup soup;
  soup.positions.reserve(points.size());
  for (const openvdb::Vec3s& p : points) soup.positions.push_back(origin + Vec3d(p.x(), p.y(), p.z()));
  const auto add = [&](Index a, Index b, Index c) { soup.triangles.push_back({a, c, b}); };
  soup.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) add(t[0], t[1], t[2]);
  for (const openvdb::Vec4I& q : quads) {
    const auto& p = soup.positions;
    if ((p[q[0]] - p[q[2]]).squaredNorm() <= (p[q[1]] - p[q[3]]).squaredNorm()) {
      add(q[0], q[1], q[2]);
      add(q[0], q[2], q[3]);
    } else {
      add(q[0], q[1], q[3]);
      add(q[1], q[2], q[3]);
    }
  }
  return soup;
}

}  // namespace

TriangleSoup outer_hull(const TriangleSoup& soup, const OuterHullOptions& options, std::size_t max_voxels) {
  if (!(options.voxel_size > 0.0) || !std::isfinite(options.voxel_size))
    throw UsageError("the outer hull's voxel size must be a positive number");
  if (!(options.wall_radius >= std::sqrt(3.0) / 2.0))
    throw UsageError("the outer hull's wall radius must be at least sqrt(3)/2 voxels");
  if (!(options.closing >= 0.0 && options.closing <= options.wall_radius - 0.5))
    throw UsageError("the outer hull's closing must be between 0 and its wall radius less half a voxel");
  if (soup.triangles.empty()) return {};
  const Vec3d origin = used_bounding_box(soup).min();
  const auto xform = openvdb::math::Transform::createLinearTransform(options.voxel_size);
  const double half_width = options.wall_radius + kBandBeyondWall;
  check_grid_fits(soup, options.voxel_size, half_width, max_voxels);
  const FloatGrid::Ptr band = distance_band(soup, origin, *xform, half_width);
  const openvdb::CoordBBox active = band->evalActiveVoxelBoundingBox();
  if (active.empty()) return {};
  const DenseBox box(active);
  const float voxel = static_cast<float>(options.voxel_size);
  const float wall = static_cast<float>(options.wall_radius * options.voxel_size);
  const WindingNumberTree winding(soup);
  const FloatGrid::Ptr level_set =
      hull_level_set(*band, box, classify(*band, box, wall, winding, origin), wall, voxel);
  if (options.closing == 0.0) return to_soup(mesh_level(*level_set, 0.0, options.adaptivity), origin);
  const FloatGrid::Ptr distance =
      signed_distance_to(mesh_level(*level_set, 0.0, 0.0), *level_set, half_width);
  return to_soup(mesh_level(*distance, -options.closing * options.voxel_size, options.adaptivity), origin);
}

}  // namespace mr::volume
