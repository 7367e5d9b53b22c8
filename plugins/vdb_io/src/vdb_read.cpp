// Level set -> mesh: OpenVDB's volumeToMesh on the chosen float grid.
#include "vdb_level_set.h"

#include <mr/core/errors.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cmath>
#include <string>

namespace mr::plugins::vdb {

void ensure_openvdb_initialized() { openvdb::initialize(); }

namespace {

using openvdb::FloatGrid;

// The grid named "surface" (what write_level_set makes), else the first
// float level set, else the first float grid of unknown class (many tools
// leave the class unset). Fog volumes and other value types are refused.
std::string choose_grid(openvdb::io::File& file, const std::string& path) {
  const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
  const openvdb::GridBase* level_set = nullptr;
  const openvdb::GridBase* unknown = nullptr;
  for (const openvdb::GridBase::Ptr& grid : *grids) {
    if (!grid || !grid->isType<FloatGrid>()) continue;
    if (grid->getName() == "surface") return grid->getName();
    if (!level_set && grid->getGridClass() == openvdb::GRID_LEVEL_SET) level_set = grid.get();
    if (!unknown && grid->getGridClass() == openvdb::GRID_UNKNOWN) unknown = grid.get();
  }
  if (level_set) return level_set->getName();
  if (unknown) return unknown->getName();
  throw InputError(path, grids->empty() ? "the file holds no grids"
                                        : "the file holds no float level-set grid (found " +
                                              std::to_string(grids->size()) + " other grids)");
}

FloatGrid::Ptr read_float_grid(const std::string& path) {
  openvdb::io::File file(path);
  // delayLoad = false: read everything now rather than map a file that may change later.
  file.open(false);
  const std::string name = choose_grid(file, path);
  FloatGrid::Ptr grid = openvdb::gridPtrCast<FloatGrid>(file.readGrid(name));
  file.close();
  if (!grid) throw InputError(path, "grid '" + name + "' could not be read as a float grid");
  return grid;
}

void check_values_finite(const FloatGrid& grid, const std::string& path) {
  for (auto it = grid.tree().cbeginValueAll(); it; ++it)
    if (!std::isfinite(*it)) throw InputError(path, "the grid holds non-finite values");
  if (!std::isfinite(grid.background())) throw InputError(path, "the grid background is not finite");
}

void add_triangle(TriangleSoup& soup, Index a, Index b, Index c) {
  // volumeToMesh winds polygons clockwise seen from outside for level sets
  // (negative inside); we want counter-clockwise, i.e. outward normals.
  soup.triangles.push_back({a, c, b});
}

// Splits along the shorter diagonal: better-shaped triangles.
void add_quad(TriangleSoup& soup, const openvdb::Vec4I& q) {
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
  TriangleSoup soup;
  soup.positions.reserve(points.size());
  for (const openvdb::Vec3s& p : points) soup.positions.emplace_back(p.x(), p.y(), p.z());
  soup.triangles.reserve(triangles.size() + 2 * quads.size());
  for (const openvdb::Vec3I& t : triangles) add_triangle(soup, t[0], t[1], t[2]);
  for (const openvdb::Vec4I& q : quads) add_quad(soup, q);
  return soup;
}

}  // namespace

TriangleSoup read_level_set(const std::filesystem::path& path, const io::LevelSetReadOptions& options) {
  if (!std::isfinite(options.isovalue)) throw UsageError("the isovalue must be a finite number");
  if (!(options.adaptivity >= 0.0 && options.adaptivity <= 1.0))
    throw UsageError("the adaptivity must be between 0 and 1");
  ensure_openvdb_initialized();
  const std::string name = path.string();
  try {
    const FloatGrid::Ptr grid = read_float_grid(name);
    check_values_finite(*grid, name);
    TriangleSoup soup = mesh_level_set(*grid, options);
    if (soup.triangles.empty())
      throw InputError(name, "the level set has no surface at isovalue " + std::to_string(options.isovalue));
    return soup;
  } catch (const Error&) {
    throw;
  } catch (const openvdb::Exception& e) {
    throw InputError(name, std::string("not a readable OpenVDB level set: ") + e.what());
  } catch (const std::bad_alloc&) {
    throw InputError(name, "corrupt OpenVDB file: it claims more data than can be allocated");
  } catch (const std::exception& e) {
    throw InputError(name, std::string("not a readable OpenVDB file: ") + e.what());
  }
}

}  // namespace mr::plugins::vdb
