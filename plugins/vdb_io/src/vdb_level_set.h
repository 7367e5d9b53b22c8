#pragma once
// Internal interface between the format registration and the two files that
// hold OpenVDB code. No OpenVDB type appears here.

#include <mr/core/scalar_field.h>
#include <mr/core/triangle_soup.h>
#include <mr/io/options.h>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace mr::plugins::vdb {

/// Writes `soup` as a narrow-band level set grid named "surface"; the sign
/// comes from the generalized winding number (inside where |w| > 1/2, so
/// that soups oriented inward throughout still make a solid).
/// Throws UsageError for invalid options, RunError when the grid cannot be made or written.
void write_level_set(const TriangleSoup& soup, const std::filesystem::path& path,
                     const io::LevelSetWriteOptions& options);

/// Meshes the level set of the chosen float grid of a .vdb file's bytes into
/// outward-oriented triangles. Throws InputError naming the file (`name`).
TriangleSoup read_level_set(std::string_view bytes, const std::string& name,
                            const io::LevelSetReadOptions& options);

/// The float grid named "sizing" of a .vdb file's bytes, else its first
/// float grid that is not a level set, sampled trilinearly in world coordinates; NaN outside the
/// grid's active voxels and their neighbours (where the grid says nothing).
/// Throws InputError naming the file (`name`).
std::shared_ptr<const ScalarField> read_scalar_field(std::string_view bytes, const std::string& name);

/// openvdb::initialize() registers grid and transform types in OpenVDB's own
/// process-wide registry, which io::File and io::Stream need before reading or writing. It is
/// idempotent and thread-safe; this is the one place that calls it.
void ensure_openvdb_initialized();

/// True if some edge of `soup` (vertices identified by position) is not
/// cancelled by an edge of opposite direction: then the winding number is not
/// integer-valued and its 1/2 level spans the holes away from the surface.
bool has_oriented_boundary(const TriangleSoup& soup);

}  // namespace mr::plugins::vdb
