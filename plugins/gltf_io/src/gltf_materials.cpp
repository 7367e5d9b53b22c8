#include "gltf_materials.h"

#include "gltf_buffer_builder.h"

#include <mr/core/errors.h>
#include <mr/io/text_encoding.h>

#include <tiny_gltf.h>

namespace mr::plugins::gltf {
namespace {

using nlohmann::json;

// The mime type the bytes themselves announce, for images given by URI.
std::string sniffed_mime_type(const std::vector<unsigned char>& bytes) {
  if (bytes.size() >= 4 && bytes[0] == 0x89 && bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G')
    return "image/png";
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image/jpeg";
  return "application/octet-stream";
}

Material::Alpha alpha_mode(const std::string& mode) {
  if (mode == "MASK") return Material::Alpha::mask;
  if (mode == "BLEND") return Material::Alpha::blend;
  return Material::Alpha::opaque;
}

const char* alpha_mode_name(Material::Alpha alpha) {
  switch (alpha) {
    case Material::Alpha::mask:
      return "MASK";
    case Material::Alpha::blend:
      return "BLEND";
    case Material::Alpha::opaque:
      break;
  }
  return "OPAQUE";
}

// The image of the material's base-colour texture, or -1.
int base_color_image(const tinygltf::Model& model, const tinygltf::Material& m, const std::string& path) {
  const tinygltf::TextureInfo& info = m.pbrMetallicRoughness.baseColorTexture;
  if (info.index < 0) return -1;
  if (info.index >= static_cast<int>(model.textures.size()))
    throw InputError(path, "material '" + m.name + "' uses texture " + std::to_string(info.index) +
                               ", which does not exist");
  const int source = model.textures[static_cast<std::size_t>(info.index)].source;
  if (source >= static_cast<int>(model.images.size()))
    throw InputError(path, "texture " + std::to_string(info.index) + " uses image " + std::to_string(source) +
                               ", which does not exist");
  if (source < 0 || info.texCoord != 0 || model.images[static_cast<std::size_t>(source)].image.empty())
    return -1;
  return source;
}

}  // namespace

void read_materials(const tinygltf::Model& model, const std::string& path, TriangleSoup& soup) {
  for (const tinygltf::Image& image : model.images)
    soup.images.push_back({image.mimeType.empty() ? sniffed_mime_type(image.image) : image.mimeType,
                           {image.image.begin(), image.image.end()}});
  for (const tinygltf::Material& m : model.materials) {
    Material material;
    material.name = m.name;
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    for (std::size_t i = 0; i < 4 && i < pbr.baseColorFactor.size(); ++i)
      material.base_color[i] = static_cast<float>(pbr.baseColorFactor[i]);
    material.base_color_image = base_color_image(model, m, path);
    material.metallic = static_cast<float>(pbr.metallicFactor);
    material.roughness = static_cast<float>(pbr.roughnessFactor);
    for (std::size_t i = 0; i < 3 && i < m.emissiveFactor.size(); ++i)
      material.emissive[i] = static_cast<float>(m.emissiveFactor[i]);
    material.alpha = alpha_mode(m.alphaMode);
    material.alpha_cutoff = static_cast<float>(m.alphaCutoff);
    material.double_sided = m.doubleSided;
    soup.materials.push_back(std::move(material));
  }
  // Images no material uses are not carried.
  std::vector<char> used(soup.images.size(), 0);
  for (const Material& m : soup.materials)
    if (m.base_color_image >= 0) used[static_cast<std::size_t>(m.base_color_image)] = 1;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (!used[i]) soup.images[i].bytes.clear();
}

json MaterialWriter::material(std::size_t region, BufferBuilder& buffer) {
  const bool named = region < soup_.region_names.size() && !soup_.region_names[region].empty();
  const std::string name =
      named ? io::as_utf8(soup_.region_names[region]) : "region_" + std::to_string(region);
  if (region >= soup_.materials.size())
    return {{"name", name}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}};
  const Material& m = soup_.materials[region];
  json pbr = {
      {"baseColorFactor", m.base_color}, {"metallicFactor", m.metallic}, {"roughnessFactor", m.roughness}};
  if (m.base_color_image >= 0 && soup_.has_uvs()) {  // a texture needs TEXCOORD_0
    const int texture = texture_of(m.base_color_image, buffer);
    if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}};
  }
  json material = {{"name", name}, {"pbrMetallicRoughness", pbr}};
  if (m.emissive != std::array<float, 3>{0.0f, 0.0f, 0.0f}) material["emissiveFactor"] = m.emissive;
  if (m.alpha != Material::Alpha::opaque) material["alphaMode"] = alpha_mode_name(m.alpha);
  if (m.alpha == Material::Alpha::mask) material["alphaCutoff"] = m.alpha_cutoff;
  if (m.double_sided) material["doubleSided"] = true;
  return material;
}

int MaterialWriter::texture_of(int image, BufferBuilder& buffer) {
  const auto i = static_cast<std::size_t>(image);
  if (i >= soup_.images.size() || soup_.images[i].bytes.empty()) return -1;
  if (texture_of_image_[i] < 0) {
    const EncodedImage& encoded = soup_.images[i];
    const int view = buffer.add_view(encoded.bytes.data(), encoded.bytes.size(), std::nullopt);
    images_.push_back({{"bufferView", view}, {"mimeType", encoded.mime_type}});
    texture_of_image_[i] = static_cast<int>(textures_.size());
    textures_.push_back({{"source", static_cast<int>(images_.size()) - 1}});
  }
  return texture_of_image_[i];
}

void MaterialWriter::finish(json& doc) const {
  if (textures_.empty()) return;
  doc["textures"] = textures_;
  doc["images"] = images_;
}

}  // namespace mr::plugins::gltf
