// Level set -> mesh: OpenVDB's volumeToMesh on the chosen float grid; and a
// float grid as a scalar field (trilinear samples in world coordinates).
#include "vdb_declared_sizes.h"
#include "vdb_level_set.h"

#include <mr/core/errors.h>
#include <mr/core/union_find.h>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace mr::plugins::vdb {

void ensure_openvdb_initialized() { openvdb::initialize(); }

namespace {

using openvdb::FloatGrid;

// The grid named "surface" (what write_level_set makes), else the first
// float level set, else the first float grid of unknown class (many tools
// leave the class unset). Fog volumes and other value types are refused.
FloatGrid::Ptr choose_grid(const openvdb::GridPtrVec& grids, const std::string& path) {
  FloatGrid::Ptr level_set, unknown;
  for (const openvdb::GridBase::Ptr& grid : grids) {
    FloatGrid::Ptr floats = openvdb::gridPtrCast<FloatGrid>(grid);
    if (!floats) continue;
    if (floats->getName() == "surface") return floats;
    if (!level_set && floats->getGridClass() == openvdb::GRID_LEVEL_SET) level_set = floats;
    if (!unknown && floats->getGridClass() == openvdb::GRID_UNKNOWN) unknown = floats;
  }
  if (level_set) return level_set;
  if (unknown) return unknown;
  throw InputError(path, grids.empty() ? "the file holds no grids"
                                       : "the file holds no float level-set grid (found " +
                                             std::to_string(grids.size()) + " other grids)");
}

// io::Stream reads what io::File writes, from memory, all grids at once
// (delayLoad = false). A read past the end throws (failbit) rather than
// leaving OpenVDB to go on with values it never read.
openvdb::GridPtrVec read_grids(std::string_view bytes, const std::string& path) {
  check_vdb_declared_sizes(bytes, path);
  std::istringstream in(std::string(bytes), std::ios::binary);
  in.exceptions(std::ios::failbit | std::ios::badbit);
  openvdb::io::Stream stream(in, false);
  const openvdb::GridPtrVecPtr grids = stream.getGrids();
  if (!grids) throw InputError(path, "the file holds no grids");
  return *grids;
}

// The grid named "sizing", else the first float grid that is not a level
// set: signed distances are no lengths (negative inside, and near zero at
// the surface, where they would ask for the finest mesh).
FloatGrid::Ptr choose_field_grid(const openvdb::GridPtrVec& grids, const std::string& path) {
  FloatGrid::Ptr first;
  bool level_sets = false;
  for (const openvdb::GridBase::Ptr& grid : grids) {
    FloatGrid::Ptr floats = openvdb::gridPtrCast<FloatGrid>(grid);
    if (!floats) continue;
    if (floats->getName() == "sizing") return floats;
    const bool level_set = floats->getGridClass() == openvdb::GRID_LEVEL_SET;
    level_sets = level_sets || level_set;
    if (!level_set && !first) first = floats;
  }
  if (first) return first;
  throw InputError(
      path, level_sets ? "the file holds only level sets (signed distances), not a float grid of "
                         "lengths (name it \"sizing\" to use it anyway)"
                       : "the file holds no float grid (found " + std::to_string(grids.size()) + " grids)");
}

class GridField : public ScalarField {
 public:
  explicit GridField(FloatGrid::Ptr grid) : grid_(std::move(grid)) {}
  // Reads a const tree without an accessor's cache: safe from any thread.
  double at(const Vec3d& p) const override {
    const openvdb::Vec3d index = grid_->worldToIndex(openvdb::Vec3d(p.x(), p.y(), p.z()));
    const openvdb::Coord nearest = openvdb::Coord::round(index);
    if (!grid_->tree().isValueOn(nearest)) return std::numeric_limits<double>::quiet_NaN();
    return openvdb::tools::BoxSampler::sample(grid_->tree(), index);
  }

 private:
  FloatGrid::Ptr grid_;
};

// Runs `read`, turning what OpenVDB and the stream throw into InputError.
template <class Read>
auto reporting_errors(const std::string& name, Read&& read) {
  try {
    return read();
  } catch (const Error&) {
    throw;
  } catch (const openvdb::Exception& e) {
    throw InputError(name, std::string("not a readable OpenVDB file: ") + e.what());
  } catch (const std::bad_alloc&) {
    throw InputError(name, "corrupt OpenVDB file: it claims more data than can be allocated");
  } catch (const std::ios_base::failure&) {
    throw InputError(name, "truncated OpenVDB file: it ends before the data it announces");
  } catch (const std::exception& e) {
    throw InputError(name, std::string("not a readable OpenVDB file: ") + e.what());
  }
}

void check_values_finite(const FloatGrid& grid, const std::string& path) {
  for (auto it = grid.tree().cbeginValueAll(); it; ++it)
    if (!std::isfinite(*it)) throw InputError(path, "the grid holds non-finite values");
  if (!std::isfinite(grid.background())) throw InputError(path, "the grid background is not finite");
}

// A level set keeps only the voxels of its narrow band active; OpenVDB's
// own check (tools::checkLevelSet) fails one with active tiles. Meshing
// meshes every side of an active tile where the sign changes: a 9 KB file
// of 128^3 tiles in a checkerboard asked for 3.1M quads, a 32^3 board of
// them would ask for 1.6 billion.
void check_no_active_tiles(const FloatGrid& grid, const std::string& path) {
  if (grid.tree().hasActiveTiles())
    throw InputError(path,
                     "the level set has active tiles (a level set keeps only the voxels of its narrow band "
                     "active)");
}

// At sharp edges and corners volumeToMesh gives a polygon corners at one
// position: such a polygon is an edge, or a triangle, rather than the face
// it names. Its corners at one position become one vertex here, and a polygon left with fewer than three
// corners is dropped: kept, a cube's surface was not watertight after welding identical positions (786
// zero-area faces at the default voxel size). Only corners of one polygon are merged: points of two sheets of
// the level set that touch stay apart, as volumeToMesh made them.
template <class Polygon>
void weld_corners(const std::vector<openvdb::Vec3s>& points, const Polygon& corners, int n, UnionFind& weld) {
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (points[corners[i]] == points[corners[j]]) weld.unite(corners[i], corners[j]);
}

void add_triangle(TriangleSoup& soup, Index a, Index b, Index c) {
  if (a == b || b == c || c == a) return;  // an edge (see weld_corners)
  // volumeToMesh winds polygons clockwise seen from outside for level sets
  // (negative inside); we want counter-clockwise, i.e. outward normals.
  soup.triangles.push_back({a, c, b});
}

// Splits along the shorter diagonal: better-shaped triangles.
void add_quad(TriangleSoup& soup, const std::array<Index, 4>& q) {
  const auto& p = soup.positions;
  if ((p[q[0]] - p[q[2]]).squaredNorm() <= (p[q[1]] - p[q[3]]).squaredNorm()) {
    add_triangle(soup, q[0], q[1], q[2]);
    add_triangle(soup, q[0], q[2], q[3]);
  } else {
    add_triangle(soup, q[0], q[1], q[3]);
    add_triangle(soup, q[1], q[2], q[3]);
  }
}

TriangleSoup mesh_level_set(const FloatGrid& grid, const io::LevelSetReadOptions& options) {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, options.isovalue, options.adaptivity);
  UnionFind weld(points.size());
  for (const openvdb::Vec3I& t : triangles) weld_corners(points, t, 3, weld);
  for (const openvdb::Vec4I& q : quads) weld_corners(points, q, 4, weld);
  TriangleSoup soup;
  soup.positions.reserve(points.size());
  for (const openvdb::Vec3s& p : points) soup.positions.emplace_back(p.x(), p.y(), p.z());
  const auto v = [&](unsigned point) { return Index(weld.find(point)); };
  soup.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) add_triangle(soup, v(t[0]), v(t[1]), v(t[2]));
  for (const openvdb::Vec4I& q : quads) add_quad(soup, {v(q[0]), v(q[1]), v(q[2]), v(q[3])});
  return soup;
}

}  // namespace

TriangleSoup read_level_set(std::string_view bytes, const std::string& name,
                            const io::LevelSetReadOptions& options) {
  if (!std::isfinite(options.isovalue)) throw UsageError("the isovalue must be a finite number");
  if (!(options.adaptivity >= 0.0 && options.adaptivity <= 1.0))
    throw UsageError("the adaptivity must be between 0 and 1");
  ensure_openvdb_initialized();
  return reporting_errors(name, [&] {
    const FloatGrid::Ptr grid = choose_grid(read_grids(bytes, name), name);
    check_values_finite(*grid, name);
    check_no_active_tiles(*grid, name);
    TriangleSoup soup = mesh_level_set(*grid, options);
    if (soup.triangles.empty())
      throw InputError(name, "the level set has no surface at isovalue " + std::to_string(options.isovalue));
    return soup;
  });
}

std::shared_ptr<const ScalarField> read_scalar_field(std::string_view bytes, const std::string& name) {
  ensure_openvdb_initialized();
  return reporting_errors(name, [&]() -> std::shared_ptr<const ScalarField> {
    FloatGrid::Ptr grid = choose_field_grid(read_grids(bytes, name), name);
    check_values_finite(*grid, name);
    return std::make_shared<GridField>(std::move(grid));
  });
}

}  // namespace mr::plugins::vdb
