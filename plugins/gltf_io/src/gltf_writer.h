#pragma once
// Writing a triangle soup as glTF 2.0: one mesh with one primitive per face
// region (each with a material named after the region), one node, one scene.
// .glb is one binary file; .gltf embeds its buffer as a base64 data URI so it
// is one file too. With options.draco.compress_gltf every primitive is
// stored with KHR_draco_mesh_compression.

#include <mr/core/triangle_soup.h>
#include <mr/io/options.h>

#include <filesystem>

namespace mr::plugins::gltf {

/// Throws RunError if the file cannot be written.
void write_gltf(const TriangleSoup& soup, const std::filesystem::path& path, const io::WriteOptions& options,
                bool glb);

}  // namespace mr::plugins::gltf
