#include "gltf_writer.h"

#include "base64.h"
#include "glb_container.h"
#include "gltf_buffer_builder.h"
#include "gltf_draco.h"
#include "gltf_materials.h"
#include "gltf_vertex_data.h"

#include <mr/core/errors.h>
#include <mr/io/output_file.h>
#include <mr/io/text_encoding.h>

#include <algorithm>
#include <map>

namespace mr::plugins::gltf {
namespace {

using nlohmann::json;

int index_component_type(std::size_t vertex_count) {
  // 65535 is the primitive restart value, which glTF forbids as an index.
  return vertex_count <= 65535 ? component_unsigned_short : component_unsigned_int;
}

json float_accessor(int view, std::size_t count, const char* type) {
  json accessor = {{"componentType", component_float}, {"count", count}, {"type", type}};
  if (view >= 0) accessor["bufferView"] = view;
  return accessor;
}

json position_accessor(int view, std::size_t count, const FloatArrays& arrays) {
  json accessor = float_accessor(view, count, "VEC3");
  accessor["min"] = arrays.min;
  accessor["max"] = arrays.max;
  return accessor;
}

class DocumentBuilder {
 public:
  DocumentBuilder(const TriangleSoup& soup, const io::WriteOptions& options)
      : soup_(soup), draco_(options.draco), origin_(position_origin(soup, options)), material_writer_(soup) {}

  json build() {
    json doc = {{"asset", {{"version", "2.0"}, {"generator", MR_GLTF_GENERATOR}}}, {"scene", 0}};
    const std::vector<RegionGroup> groups = group_by_region(soup_);
    if (soup_.has_face_regions()) assign_materials(groups);
    json primitives = json::array();
    if (!soup_.triangles.empty())
      primitives = draco_.compress_gltf ? draco_primitives(groups) : plain_primitives(groups);
    if (primitives.empty()) {
      doc["scenes"] = json::array({json::object()});
      return doc;
    }
    doc["scenes"] = json::array({{{"nodes", {0}}}});
    json node = {{"mesh", 0}};
    if (origin_ != Vec3d::Zero()) node["translation"] = {origin_.x(), origin_.y(), origin_.z()};
    doc["nodes"] = json::array({node});
    doc["meshes"] = json::array({{{"primitives", primitives}}});
    if (!materials_.empty()) doc["materials"] = materials_;
    material_writer_.finish(doc);
    if (draco_.compress_gltf) {
      doc["extensionsUsed"] = {draco_extension};
      doc["extensionsRequired"] = {draco_extension};
    }
    doc["accessors"] = buffer_.accessors();
    doc["bufferViews"] = buffer_.views();
    return doc;
  }

  const std::vector<char>& bytes() const { return buffer_.bytes(); }

 private:
  json primitive(json attributes, int indices, int region) const {
    json p = {{"attributes", std::move(attributes)}, {"indices", indices}, {"mode", 4}};
    if (region >= 0) p["material"] = material_of_region_.at(region);
    return p;
  }

  // Vertex attributes shared by all primitives; one index accessor per region.
  json plain_primitives(const std::vector<RegionGroup>& groups) {
    const FloatArrays a = float_arrays(soup_, origin_);
    const std::size_t n = soup_.num_vertices();
    json attributes;
    const auto add = [&](const char* name, const std::vector<float>& values, const char* type) {
      const int view = buffer_.add_view(values.data(), values.size() * sizeof(float), array_buffer);
      attributes[name] = buffer_.add_accessor(float_accessor(view, n, type));
    };
    attributes["POSITION"] = buffer_.add_accessor(
        position_accessor(buffer_.add_view(a.positions.data(), a.positions.size() * 4, array_buffer), n, a));
    if (soup_.has_normals()) add("NORMAL", a.normals, "VEC3");
    if (soup_.has_uvs()) add("TEXCOORD_0", a.uvs, "VEC2");
    if (soup_.has_colors()) add("COLOR_0", a.colors, "VEC4");
    if (soup_.has_face_sources()) add(kSourceFaceAttribute, a.sources, "SCALAR");

    const int component = index_component_type(n);
    const std::size_t index_size = component == component_unsigned_short ? 2 : 4;
    std::vector<char> index_bytes;
    std::vector<std::size_t> offsets;
    for (const RegionGroup& group : groups) {
      offsets.push_back(index_bytes.size());
      for (const Triangle& t : group.triangles)
        for (Index v : t) append_index(index_bytes, v, index_size);
    }
    const int view = buffer_.add_view(index_bytes.data(), index_bytes.size(), element_array_buffer);
    json primitives = json::array();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const int accessor = buffer_.add_accessor({{"bufferView", view},
                                                 {"byteOffset", offsets[g]},
                                                 {"componentType", component},
                                                 {"count", 3 * groups[g].triangles.size()},
                                                 {"type", "SCALAR"}});
      primitives.push_back(primitive(attributes, accessor, groups[g].region));
    }
    return primitives;
  }

  static void append_index(std::vector<char>& out, Index v, std::size_t size) {
    if (size == 2) {
      const auto s = static_cast<std::uint16_t>(v);
      out.insert(out.end(), reinterpret_cast<const char*>(&s), reinterpret_cast<const char*>(&s) + 2);
    } else {
      out.insert(out.end(), reinterpret_cast<const char*>(&v), reinterpret_cast<const char*>(&v) + 4);
    }
  }

  // Each region is its own Draco mesh; its accessors carry counts and bounds but no data.
  json draco_primitives(const std::vector<RegionGroup>& groups) {
    json primitives = json::array();
    for (const RegionGroup& group : groups) {
      const TriangleSoup part = groups.size() == 1 ? soup_ : sub_soup(soup_, group.triangles);
      const DracoPrimitive encoded = encode_draco_primitive(part, draco_);
      const FloatArrays a = float_arrays(part);
      const std::size_t n = encoded.vertex_count;
      json attributes;
      for (const auto& [name, id] : encoded.attribute_ids) {
        json accessor = name == "POSITION"     ? position_accessor(-1, n, a)
                        : name == "TEXCOORD_0" ? float_accessor(-1, n, "VEC2")
                        : name == "COLOR_0"    ? float_accessor(-1, n, "VEC4")
                                               : float_accessor(-1, n, "VEC3");
        attributes[name] = buffer_.add_accessor(std::move(accessor));
      }
      const int indices = buffer_.add_accessor({{"componentType", index_component_type(n)},
                                                {"count", 3 * part.triangles.size()},
                                                {"type", "SCALAR"}});
      json p = primitive(attributes, indices, group.region);
      const int view = buffer_.add_view(encoded.bytes.data(), encoded.bytes.size(), std::nullopt);
      p["extensions"][draco_extension] = {{"bufferView", view}, {"attributes", encoded.attribute_ids}};
      primitives.push_back(std::move(p));
    }
    return primitives;
  }

  // Material i is region i, so ids survive a round trip; but sparse huge ids
  // (a region 2^30 on one face) are renumbered rather than padded with
  // millions of unused materials.
  void assign_materials(const std::vector<RegionGroup>& groups) {
    const std::size_t names = soup_.region_names.size();
    const int max_region = groups.empty() ? -1 : groups.back().region;
    const bool dense = static_cast<std::size_t>(max_region + 1) <= names + groups.size() + 1024;
    std::size_t count = dense ? std::max(names, static_cast<std::size_t>(max_region + 1)) : 0;
    for (const RegionGroup& group : groups)
      if (group.region >= 0)
        material_of_region_[group.region] = dense ? group.region : static_cast<int>(count++);
    if (dense) {
      for (std::size_t i = 0; i < count; ++i) materials_.push_back(material_writer_.material(i, buffer_));
    } else {
      for (const auto& [region, index] : material_of_region_)
        materials_.push_back(material_writer_.material(static_cast<std::size_t>(region), buffer_));
    }
  }

  // Where positions are stored relative to (the node's translation): the
  // origin of a float32 grid about one, zero for plain floats and Draco.
  static Vec3d position_origin(const TriangleSoup& soup, const io::WriteOptions& options) {
    if (options.draco.compress_gltf || soup.positions.empty()) return Vec3d::Zero();
    if (options.gltf_position_grid) return options.gltf_position_grid->origin();
    const Eigen::AlignedBox3d box = bounding_box(soup);
    return CoordinateGrid::float32_over(box.min(), box.max()).origin();
  }

  const TriangleSoup& soup_;
  const io::DracoOptions& draco_;
  Vec3d origin_;
  BufferBuilder buffer_;
  MaterialWriter material_writer_;
  std::map<int, int> material_of_region_;
  json materials_ = json::array();
};

TriangleSoup without_face_sources(TriangleSoup soup) {
  soup.face_sources.clear();
  return soup;
}

}  // namespace

void write_gltf(const TriangleSoup& soup, const std::filesystem::path& path, const io::WriteOptions& options,
                bool glb) {
  // Face sources need vertices of their own per face; Draco reorders faces
  // and does not carry them.
  TriangleSoup clean = sanitized_for_gltf(soup);
  if (clean.has_face_sources())
    clean = options.draco.compress_gltf ? without_face_sources(clean) : with_own_vertices(clean);
  DocumentBuilder builder(clean, options);
  json doc = builder.build();
  const std::vector<char>& bin = builder.bytes();
  if (!bin.empty()) {
    json buffer = {{"byteLength", bin.size()}};
    if (!glb)
      buffer["uri"] = "data:application/octet-stream;base64," + base64_encode({bin.data(), bin.size()});
    doc["buffers"] = json::array({buffer});
  }
  const std::string text = doc.dump();
  if (glb && bin.size() + text.size() > 0xFFFFFF00ull)
    throw RunError("cannot write " + path.string() + ": a GLB file must stay under 4 GB");
  if (!glb) return io::write_file_bytes(path, text);
  const std::vector<char> file = assemble_glb(text, {bin.data(), bin.size()});
  io::write_file_bytes(path, {file.data(), file.size()});
}

}  // namespace mr::plugins::gltf
