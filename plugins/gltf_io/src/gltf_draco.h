#pragma once
// KHR_draco_mesh_compression: decoding a primitive on read and encoding one
// on write, through mr_plugin_draco's codec. Without MR_WITH_DRACO both
// report that this build lacks Draco support.

#include <mr/core/triangle_soup.h>
#include <mr/io/options.h>

#include <tiny_gltf.h>

#include <map>
#include <string>
#include <vector>

namespace mr::plugins::gltf {

inline constexpr const char* draco_extension = "KHR_draco_mesh_compression";

bool is_draco_primitive(const tinygltf::Primitive& primitive);

/// The primitive's mesh, untransformed. Throws InputError naming `path`.
TriangleSoup decode_draco_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& path);

struct DracoPrimitive {
  std::vector<char> bytes;
  std::map<std::string, int> attribute_ids;  ///< glTF attribute name -> Draco unique id
  std::size_t vertex_count = 0;              ///< points in the encoded mesh, as a decoder will return them
};

/// Throws RunError if Draco cannot encode `soup` or this build has no Draco.
DracoPrimitive encode_draco_primitive(const TriangleSoup& soup, const io::DracoOptions& options);

}  // namespace mr::plugins::gltf
