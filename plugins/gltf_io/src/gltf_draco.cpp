#include "gltf_draco.h"

#include <mr/core/errors.h>

#ifdef MR_WITH_DRACO
#include <mr/plugins/draco_codec.h>
#endif

namespace mr::plugins::gltf {
namespace {

[[maybe_unused]] int attribute_id(const tinygltf::Value& attributes, const char* name,
                                  const std::string& path) {
  if (!attributes.Has(name)) return -1;
  const tinygltf::Value& id = attributes.Get(name);
  if (!id.IsInt() || id.Get<int>() < 0)
    throw InputError(
        path, std::string(draco_extension) + ": attribute id of " + name + " is not a non-negative integer");
  return id.Get<int>();
}

// The bytes of the extension's bufferView, checked to lie inside their buffer.
[[maybe_unused]] std::string_view draco_bytes(const tinygltf::Model& model, const tinygltf::Value& extension,
                                              const std::string& path) {
  const std::string prefix = std::string(draco_extension) + ": ";
  if (!extension.Has("bufferView") || !extension.Get("bufferView").IsInt())
    throw InputError(path, prefix + "bufferView is missing");
  const int view = extension.Get("bufferView").Get<int>();
  if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size())
    throw InputError(path, prefix + "bufferView " + std::to_string(view) + " does not exist");
  const tinygltf::BufferView& buffer_view = model.bufferViews[static_cast<std::size_t>(view)];
  if (buffer_view.buffer < 0 || static_cast<std::size_t>(buffer_view.buffer) >= model.buffers.size())
    throw InputError(
        path, prefix + "bufferView " + std::to_string(view) + " refers to a buffer that does not exist");
  const auto& buffer = model.buffers[static_cast<std::size_t>(buffer_view.buffer)].data;
  if (buffer_view.byteOffset > buffer.size() ||
      buffer_view.byteLength > buffer.size() - buffer_view.byteOffset)
    throw InputError(path, prefix + "bufferView " + std::to_string(view) + " lies outside its buffer");
  return {reinterpret_cast<const char*>(buffer.data()) + buffer_view.byteOffset, buffer_view.byteLength};
}

}  // namespace

bool is_draco_primitive(const tinygltf::Primitive& primitive) {
  return primitive.extensions.count(draco_extension) != 0;
}

#ifdef MR_WITH_DRACO

TriangleSoup decode_draco_primitive(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                    const std::string& path) {
  const tinygltf::Value& extension = primitive.extensions.at(draco_extension);
  if (!extension.IsObject()) throw InputError(path, std::string(draco_extension) + " is not a JSON object");
  DracoAttributeIds ids;
  if (extension.Has("attributes")) {
    const tinygltf::Value& attributes = extension.Get("attributes");
    if (!attributes.IsObject())
      throw InputError(path, std::string(draco_extension) + ": attributes is not a JSON object");
    ids.position = attribute_id(attributes, "POSITION", path);
    ids.normal = attribute_id(attributes, "NORMAL", path);
    ids.uv = attribute_id(attributes, "TEXCOORD_0", path);
    ids.color = attribute_id(attributes, "COLOR_0", path);
  }
  TriangleSoup soup = decode_draco(draco_bytes(model, extension, path), path, ids);
  // Attributes the primitive does not declare are not part of the glTF mesh.
  if (!primitive.attributes.count("NORMAL")) soup.normals.clear();
  if (!primitive.attributes.count("TEXCOORD_0")) soup.uvs.clear();
  if (!primitive.attributes.count("COLOR_0")) soup.colors.clear();
  return soup;
}

DracoPrimitive encode_draco_primitive(const TriangleSoup& soup, const io::DracoOptions& options) {
  DracoEncoded encoded = encode_draco(soup, options);
  DracoPrimitive result;
  const auto add = [&](const char* name, int id) {
    if (id >= 0) result.attribute_ids[name] = id;
  };
  add("POSITION", encoded.ids.position);
  add("NORMAL", encoded.ids.normal);
  add("TEXCOORD_0", encoded.ids.uv);
  add("COLOR_0", encoded.ids.color);
  // Draco may drop or split points: the accessors state what a decoder returns.
  result.vertex_count = encoded.num_points;
  result.bytes = std::move(encoded.bytes);
  return result;
}

#else

TriangleSoup decode_draco_primitive(const tinygltf::Model&, const tinygltf::Primitive&,
                                    const std::string& path) {
  throw InputError(path, std::string("uses ") + draco_extension + ", but this build has no Draco support");
}

DracoPrimitive encode_draco_primitive(const TriangleSoup&, const io::DracoOptions&) {
  throw RunError(std::string("cannot write ") + draco_extension + ": this build has no Draco support");
}

#endif

}  // namespace mr::plugins::gltf
