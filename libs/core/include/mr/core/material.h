#pragma once
// Materials as asset formats share them: glTF 2.0's metal-rough model with
// a base-colour texture, the part of it every viewer draws. Images are kept
// encoded (PNG or JPEG bytes as the file held them): the toolkit never
// needs their pixels, only to hand them on.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mr {

struct EncodedImage {
  std::string mime_type;  ///< "image/png", "image/jpeg", ...
  std::vector<std::uint8_t> bytes;
};

struct Material {
  enum class Alpha { opaque, mask, blend };

  std::string name;
  std::array<float, 4> base_color{1.0f, 1.0f, 1.0f, 1.0f};
  /// Index into TriangleSoup::images of the base-colour texture (read with
  /// the first texture coordinates), or -1.
  int base_color_image = -1;
  float metallic = 1.0f;
  float roughness = 1.0f;
  std::array<float, 3> emissive{0.0f, 0.0f, 0.0f};
  Alpha alpha = Alpha::opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
};

}  // namespace mr
