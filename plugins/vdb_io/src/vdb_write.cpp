// Mesh -> narrow-band level set. OpenVDB makes the unsigned distance band;
// the sign comes from the fast winding number, which is what lets open,
// self-intersecting and inconsistently oriented soups produce a closed solid.
#include "vdb_level_set.h"

#include <mr/core/errors.h>
#include <mr/winding_number/winding_number.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <unordered_set>

namespace mr::plugins::vdb {
namespace {

using openvdb::Coord;
using openvdb::FloatGrid;

// Narrow bands beyond this many voxels would need tens of gigabytes.
constexpr double max_band_voxels = 4e8;
// Index coordinates must stay well inside OpenVDB's 32-bit range.
constexpr double max_index_coordinate = 1 << 30;

struct GridSpec {
  double voxel_size = 0.0;
  double half_width = 0.0;  ///< in voxels
};

double total_area(const TriangleSoup& soup) {
  double area = 0.0;
  for (const Triangle& t : soup.triangles) {
    const Vec3d &a = soup.positions[t[0]], &b = soup.positions[t[1]], &c = soup.positions[t[2]];
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

GridSpec validated_spec(const TriangleSoup& soup, const io::LevelSetWriteOptions& options) {
  if (!std::isfinite(options.voxel_size) || options.voxel_size < 0.0)
    throw UsageError("the level set voxel size must be a positive number (or 0 for the default)");
  if (!std::isfinite(options.half_width) || options.half_width < 1.0 || options.half_width > 1000.0)
    throw UsageError("the level set half width must be between 1 and 1000 voxels");
  if (soup.triangles.empty()) throw RunError("cannot make a level set of a mesh without triangles");
  GridSpec spec{options.voxel_size, options.half_width};
  if (spec.voxel_size == 0.0) spec.voxel_size = bounding_box_diagonal(soup) / 256.0;
  if (!(spec.voxel_size > 0.0) || !std::isfinite(spec.voxel_size))
    throw RunError("cannot choose a voxel size: the mesh has no extent (give one with --voxel-size)");
  double max_coordinate = 0.0;
  for (const Vec3d& p : soup.positions) max_coordinate = std::max(max_coordinate, p.cwiseAbs().maxCoeff());
  if (max_coordinate / spec.voxel_size > max_index_coordinate || max_coordinate > 1e30)
    throw UsageError("the voxel size " + std::to_string(spec.voxel_size) +
                     " is too small for coordinates up to " + std::to_string(max_coordinate));
  const double band_voxels = (total_area(soup) / (spec.voxel_size * spec.voxel_size) + soup.num_triangles()) *
                             2.0 * (spec.half_width + 1.0);
  if (band_voxels > max_band_voxels)
    throw UsageError("the voxel size " + std::to_string(spec.voxel_size) + " would need about " +
                     std::to_string(static_cast<long long>(band_voxels)) + " voxels: choose a larger one");
  return spec;
}

FloatGrid::Ptr unsigned_band(const TriangleSoup& soup, const openvdb::math::Transform& xform,
                             double half_width) {
  std::vector<openvdb::Vec3s> points;
  points.reserve(soup.positions.size());
  for (const Vec3d& p : soup.positions) points.emplace_back(float(p.x()), float(p.y()), float(p.z()));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  return openvdb::tools::meshToUnsignedDistanceField<FloatGrid>(xform, points, triangles, {},
                                                                static_cast<float>(half_width));
}

Vec3d world_position(const openvdb::math::Transform& xform, const Coord& ijk) {
  const openvdb::Vec3d p = xform.indexToWorld(ijk);
  return {p.x(), p.y(), p.z()};
}

// Negative inside (|w| > 1/2), positive outside, magnitude from the band.
// |w| rather than w: a soup whose faces all point inward (common in the wild)
// has w = -1 inside and still describes a solid.
void sign_band(FloatGrid& grid, const WindingNumberTree& winding) {
  openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
  const openvdb::math::Transform& xform = grid.transform();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i)
      for (auto it = leaves.leaf(i).beginValueOn(); it; ++it) {
        const float distance = std::abs(*it);
        it.setValue(std::abs(winding.evaluate(world_position(xform, it.getCoord()))) > 0.5 ? -distance
                                                                                           : distance);
      }
  });
}

// A block is an 8^3 cube of voxels aligned like OpenVDB's leaf nodes.
constexpr int block_dim = 8;

struct BlockResult {
  std::vector<std::pair<Coord, float>> voxels;  ///< new band voxels spanning a hole
  int grow_faces = 0;                           ///< bit f set: continue across face f
};

// Where the soup has holes the 1/2 level of the winding number leaves the
// surface and spans them. Near that level, far from the surface, the signed
// distance is approximated by (|w| - 1/2) / |grad |w|| with central differences.
BlockResult span_holes_in_block(const FloatGrid& band, const WindingNumberTree& winding, const Coord& origin,
                                double half_width) {
  constexpr int padded = block_dim + 2;
  std::vector<double> w(padded * padded * padded);
  const auto at = [&](int x, int y, int z) -> double& {
    return w[((x + 1) * padded + (y + 1)) * padded + (z + 1)];
  };
  for (int x = -1; x <= block_dim; ++x)
    for (int y = -1; y <= block_dim; ++y)
      for (int z = -1; z <= block_dim; ++z)
        at(x, y, z) = std::abs(winding.evaluate(world_position(band.transform(), origin.offsetBy(x, y, z))));
  BlockResult result;
  auto accessor = band.getConstAccessor();
  const double voxel = band.voxelSize()[0];
  for (int x = 0; x < block_dim; ++x)
    for (int y = 0; y < block_dim; ++y)
      for (int z = 0; z < block_dim; ++z) {
        const Coord ijk = origin.offsetBy(x, y, z);
        if (accessor.isValueOn(ijk)) continue;
        const Vec3d gradient(at(x + 1, y, z) - at(x - 1, y, z), at(x, y + 1, z) - at(x, y - 1, z),
                             at(x, y, z + 1) - at(x, y, z - 1));
        const double slope = 0.5 * gradient.norm();
        const double inside_voxels = (at(x, y, z) - 0.5) / std::max(slope, 1e-12);
        if (std::abs(inside_voxels) >= half_width) continue;
        result.voxels.emplace_back(ijk, static_cast<float>(-inside_voxels * voxel));
        const int faces[6] = {x == 0, x == block_dim - 1, y == 0, y == block_dim - 1,
                              z == 0, z == block_dim - 1};
        for (int f = 0; f < 6; ++f) result.grow_faces |= faces[f] << f;
      }
  return result;
}

// Grows from the band's leaves across block faces while the hole-spanning
// band continues, in parallel rounds; the set of blocks and their values do
// not depend on the thread count.
void add_hole_spanning_band(FloatGrid& grid, const WindingNumberTree& winding, double half_width) {
  std::vector<Coord> frontier;
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) frontier.push_back(leaf->origin());
  std::unordered_set<Coord> visited;
  for (const Coord& origin : frontier) visited.insert(origin);
  const std::size_t max_blocks = std::max<std::size_t>(1 << 20, 64 * frontier.size());
  std::vector<std::pair<Coord, float>> spanning;
  while (!frontier.empty()) {
    std::vector<BlockResult> results(frontier.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frontier.size()), [&](const auto& range) {
      for (std::size_t i = range.begin(); i != range.end(); ++i)
        results[i] = span_holes_in_block(grid, winding, frontier[i], half_width);
    });
    std::vector<Coord> next;
    for (std::size_t i = 0; i < frontier.size(); ++i) {
      spanning.insert(spanning.end(), results[i].voxels.begin(), results[i].voxels.end());
      for (int f = 0; f < 6; ++f) {
        if (!(results[i].grow_faces >> f & 1)) continue;
        Coord neighbour = frontier[i];
        neighbour[f / 2] += f % 2 ? block_dim : -block_dim;
        if (visited.insert(neighbour).second) next.push_back(neighbour);
      }
    }
    if (visited.size() > max_blocks)
      throw RunError("the level set of the holes of this mesh does not close up");
    frontier = std::move(next);
  }
  auto accessor = grid.getAccessor();
  for (const auto& [ijk, value] : spanning) accessor.setValueOn(ijk, value);
}

// OpenVDB writes a random UUID into every file header (36 characters after
// the 21-byte magic and version fields). Replacing it by one derived from the
// rest of the file makes the same input give the same bytes, run after run.
void make_uuid_deterministic(const std::filesystem::path& path) {
  constexpr std::streamoff uuid_offset = 21;
  constexpr std::size_t uuid_length = 36;
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (bytes.size() < uuid_offset + uuid_length) return;
  const std::string_view uuid(bytes.data() + uuid_offset, uuid_length);
  if (uuid[8] != '-' || uuid[13] != '-' || uuid[18] != '-' || uuid[23] != '-') return;
  std::uint64_t hashes[2] = {14695981039346656037ull, 1099511628211ull * 31};  // FNV-1a, two seeds
  for (std::size_t i = uuid_offset + uuid_length; i < bytes.size(); ++i)
    for (std::uint64_t& h : hashes) h = (h ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
  std::string replacement;
  for (std::size_t i = 0; i < 32; ++i) {
    if (i == 8 || i == 12 || i == 16 || i == 20) replacement += '-';
    replacement += "0123456789abcdef"[hashes[i / 16] >> (4 * (i % 16)) & 0xf];
  }
  file.clear();
  file.seekp(uuid_offset);
  file.write(replacement.data(), static_cast<std::streamsize>(replacement.size()));
  if (!file) throw RunError("cannot write " + path.string());
}

}  // namespace

void write_level_set(const TriangleSoup& soup, const std::filesystem::path& path,
                     const io::LevelSetWriteOptions& options) {
  const GridSpec spec = validated_spec(soup, options);
  ensure_openvdb_initialized();
  FloatGrid::Ptr grid;
  try {
    grid = unsigned_band(soup, *openvdb::math::Transform::createLinearTransform(spec.voxel_size),
                         spec.half_width);
    const WindingNumberTree winding(soup);
    sign_band(*grid, winding);
    if (has_oriented_boundary(soup)) add_hole_spanning_band(*grid, winding, spec.half_width);
    openvdb::tools::signedFloodFill(grid->tree());
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setName("surface");
  } catch (const openvdb::Exception& e) {
    throw RunError("cannot make a level set for " + path.string() + ": " + e.what());
  }
  try {
    openvdb::io::File file(path.string());
    file.write(openvdb::GridCPtrVec{grid});
    file.close();
  } catch (const openvdb::Exception& e) {
    throw RunError("cannot write " + path.string() + ": " + e.what());
  }
  make_uuid_deterministic(path);
}

}  // namespace mr::plugins::vdb
