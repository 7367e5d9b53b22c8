#pragma once
// Parses a .gltf or .glb file's bytes into a tinygltf::Model, turning every
// problem tinygltf reports into an InputError naming the file. The model's
// contents are NOT validated here beyond what tinygltf does: the reader checks
// every index, offset and length before use.

#include <tiny_gltf.h>

#include <filesystem>
#include <string_view>

namespace mr::plugins::gltf {

/// `require_glb`: the file was named or forced as GLB, so it must carry the
/// GLB magic. Otherwise GLB content is still recognised by its magic.
/// External buffers are looked up next to `path`.
tinygltf::Model load_model(std::string_view bytes, const std::filesystem::path& path, bool require_glb);

}  // namespace mr::plugins::gltf
