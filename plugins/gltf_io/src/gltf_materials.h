#pragma once
// glTF materials to and from mr::Material: the metal-rough factors, the
// base-colour texture with its image (kept encoded), alpha and sidedness.
// Other textures (normal, occlusion, emissive maps) are not carried.

#include <mr/core/triangle_soup.h>

#include <nlohmann/json.hpp>

#include <string>

namespace tinygltf {
class Model;
}

namespace mr::plugins::gltf {

class BufferBuilder;

/// soup.materials (one per glTF material) and soup.images. A texture or
/// image index out of range is mr::InputError naming `path`; a texture
/// read through other coordinates than TEXCOORD_0, or an image the file
/// does not embed, is left out.
void read_materials(const tinygltf::Model& model, const std::string& path, TriangleSoup& soup);

/// The materials of a document being written, with the textures and
/// images they use; images go into the binary buffer (a .gltf file embeds
/// that buffer as a data URI).
class MaterialWriter {
 public:
  explicit MaterialWriter(const TriangleSoup& soup)
      : soup_(soup), texture_of_image_(soup.images.size(), -1) {}

  /// The glTF material for region `region`: the soup's material when it has
  /// one (its texture only if the soup has UVs), else a plain one named
  /// after the region.
  nlohmann::json material(std::size_t region, BufferBuilder& buffer);
  /// Adds the "textures" and "images" arrays the materials used, if any.
  void finish(nlohmann::json& doc) const;

 private:
  int texture_of(int image, BufferBuilder& buffer);

  const TriangleSoup& soup_;
  std::vector<int> texture_of_image_;  // per soup image: its glTF texture, or -1
  nlohmann::json textures_ = nlohmann::json::array();
  nlohmann::json images_ = nlohmann::json::array();
};

}  // namespace mr::plugins::gltf
