#include "gltf_reader.h"

#include "gltf_accessors.h"
#include "gltf_draco.h"
#include "gltf_load.h"
#include "gltf_materials.h"
#include "gltf_scene.h"
#include "gltf_soup_builder.h"
#include "gltf_vertex_data.h"

#include <mr/core/errors.h>

#include <array>
#include <cmath>
#include <map>

namespace mr::plugins::gltf {
namespace {

// Extensions that change what the geometry is; ignoring one that a file
// requires would read wrong triangles. Those not listed here only affect
// appearance (materials, textures, lights) and are safely ignored.
bool changes_geometry(const std::string& extension) {
  return extension != draco_extension && extension != "KHR_mesh_quantization" &&
         extension.rfind("KHR_materials_", 0) != 0 && extension.rfind("KHR_texture_", 0) != 0 &&
         extension.rfind("EXT_texture_", 0) != 0 && extension != "KHR_lights_punctual";
}

void check_required_extensions(const tinygltf::Model& model, const std::string& path) {
  for (const std::string& extension : model.extensionsRequired)
    if (changes_geometry(extension))
      throw InputError(path, "requires the unsupported glTF extension " + extension);
}

int attribute(const tinygltf::Primitive& primitive, const char* name) {
  const auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

// The vertex attributes of a non-Draco primitive, in the mesh's own frame.
TriangleSoup read_vertices(const AccessorReader& reader, const tinygltf::Primitive& primitive) {
  TriangleSoup soup;
  int components = 0;
  const std::vector<float> positions =
      reader.read_floats(attribute(primitive, "POSITION"), {3}, components, "POSITION");
  soup.positions.resize(positions.size() / 3);
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    soup.positions[i] = Vec3d(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    if (!soup.positions[i].allFinite())
      reader.fail("POSITION accessor " + std::to_string(attribute(primitive, "POSITION")) +
                  " holds a non-finite coordinate (NaN or infinity) at vertex " + std::to_string(i));
  }
  const std::size_t n = soup.positions.size();
  const auto read = [&](const char* name, std::initializer_list<int> allowed) {
    std::vector<float> values = reader.read_floats(attribute(primitive, name), allowed, components, name);
    if (values.size() != n * static_cast<std::size_t>(components))
      reader.fail(std::string(name) + " accessor " + std::to_string(attribute(primitive, name)) + " has " +
                  std::to_string(values.size() / static_cast<std::size_t>(components)) +
                  " elements but POSITION has " + std::to_string(n));
    return values;
  };
  if (attribute(primitive, "NORMAL") >= 0) {
    const std::vector<float> v = read("NORMAL", {3});
    for (std::size_t i = 0; i < n; ++i) soup.normals.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  }
  if (attribute(primitive, "TEXCOORD_0") >= 0) {
    const std::vector<float> v = read("TEXCOORD_0", {2});
    for (std::size_t i = 0; i < n; ++i) soup.uvs.emplace_back(v[2 * i], v[2 * i + 1]);
  }
  if (attribute(primitive, "COLOR_0") >= 0) {
    const std::vector<float> v = read("COLOR_0", {3, 4});
    const auto c = static_cast<std::size_t>(components);
    for (std::size_t i = 0; i < n; ++i)
      soup.colors.emplace_back(v[c * i], v[c * i + 1], v[c * i + 2], c == 4 ? v[c * i + 3] : 1.0f);
  }
  return soup;
}

// Per triangle, the _SOURCE_FACE value of its first corner (meshrepair
// writes it on every corner of the face); empty without the attribute.
std::vector<std::int64_t> face_sources(const AccessorReader& reader, const tinygltf::Primitive& primitive,
                                       const std::vector<Triangle>& triangles, std::size_t vertex_count) {
  const int accessor = attribute(primitive, kSourceFaceAttribute);
  if (accessor < 0) return {};
  int components = 0;
  const std::vector<float> values = reader.read_floats(accessor, {1}, components, kSourceFaceAttribute);
  if (values.size() != vertex_count)
    reader.fail(std::string(kSourceFaceAttribute) + " accessor " + std::to_string(accessor) + " has " +
                std::to_string(values.size()) + " elements but POSITION has " + std::to_string(vertex_count));
  std::vector<std::int64_t> sources;
  sources.reserve(triangles.size());
  for (const Triangle& t : triangles) {
    const float value = values[t[0]];
    sources.push_back(std::isfinite(value) && value >= -1.0f && value <= 16777216.0f ? std::int64_t(value)
                                                                                     : -1);
  }
  return sources;
}

// Triangles of one primitive, following the glTF spec's definitions of each mode.
std::vector<Triangle> assemble_triangles(const std::vector<Index>& v, int mode) {
  std::vector<Triangle> triangles;
  const std::size_t n = v.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    triangles.reserve(n / 3);
    for (std::size_t i = 0; i + 2 < n; i += 3) triangles.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t i = 0; i + 2 < n; ++i)  // odd triangles swap their last two vertices to keep the winding
      triangles.push_back(i % 2 == 0 ? Triangle{v[i], v[i + 1], v[i + 2]}
                                     : Triangle{v[i], v[i + 2], v[i + 1]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    for (std::size_t i = 0; i + 2 < n; ++i) triangles.push_back({v[i + 1], v[i + 2], v[0]});
  }
  return triangles;
}

std::vector<Index> primitive_indices(const AccessorReader& reader, const tinygltf::Primitive& primitive,
                                     std::size_t vertex_count) {
  if (primitive.indices >= 0) return reader.read_indices(primitive.indices, vertex_count);
  std::vector<Index> sequential(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i) sequential[i] = static_cast<Index>(i);
  return sequential;
}

bool is_triangle_mode(int mode, const std::string& path) {
  if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN)
    throw InputError(path, "invalid primitive mode " + std::to_string(mode));
  return mode >= TINYGLTF_MODE_TRIANGLES;  // POINTS and LINE* hold no surface: skipped
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path)
      : model_(model), path_(path), accessors_(model, path_), builder_(path_, buffer_bytes(model)) {}

  TriangleSoup read() {
    check_required_extensions(model_, path_);
    const std::vector<MeshInstance> instances = mesh_instances(model_, path_);
    for (std::size_t i = 0; i < instances.size(); ++i) add_instance(instances[i]);
    TriangleSoup soup = builder_.finish(material_names());
    if (soup.has_face_regions()) read_materials(model_, path_, soup);
    return soup;
  }

 private:
  static std::size_t buffer_bytes(const tinygltf::Model& model) {
    std::size_t total = 0;
    for (const tinygltf::Buffer& buffer : model.buffers) total += buffer.data.size();
    return total;
  }

  void add_instance(const MeshInstance& instance) {
    const Transform transform(instance.world);
    // Primitives of one instance that share their vertex accessors share vertices.
    std::map<std::array<int, 4>, Index> shared;
    for (const tinygltf::Primitive& primitive :
         model_.meshes[static_cast<std::size_t>(instance.mesh)].primitives) {
      if (!is_triangle_mode(primitive.mode, path_)) continue;
      const int material = checked_material(primitive.material);
      if (is_draco_primitive(primitive)) {
        TriangleSoup soup = decode_draco_primitive(model_, primitive, path_);
        const Index base = builder_.add_vertices(soup, transform);
        builder_.add_triangles(soup.triangles, base, material, transform);
        continue;
      }
      if (attribute(primitive, "POSITION") < 0) continue;  // nothing to draw
      const std::array<int, 4> key{attribute(primitive, "POSITION"), attribute(primitive, "NORMAL"),
                                   attribute(primitive, "TEXCOORD_0"), attribute(primitive, "COLOR_0")};
      auto found = shared.find(key);
      if (found == shared.end())
        found =
            shared.emplace(key, builder_.add_vertices(read_vertices(accessors_, primitive), transform)).first;
      const std::size_t vertex_count = accessors_.count(key[0], "POSITION");
      const std::vector<Triangle> triangles =
          assemble_triangles(primitive_indices(accessors_, primitive, vertex_count), primitive.mode);
      builder_.add_triangles(triangles, found->second, material, transform,
                             face_sources(accessors_, primitive, triangles, vertex_count));
    }
  }

  int checked_material(int material) const {
    if (material >= static_cast<int>(model_.materials.size()))
      throw InputError(
          path_, "a primitive refers to material " + std::to_string(material) + ", which does not exist");
    return material < 0 ? -1 : material;
  }

  std::vector<std::string> material_names() const {
    std::vector<std::string> names;
    for (std::size_t i = 0; i < model_.materials.size(); ++i)
      names.push_back(model_.materials[i].name.empty() ? "material_" + std::to_string(i)
                                                       : model_.materials[i].name);
    return names;
  }

  const tinygltf::Model& model_;
  std::string path_;
  AccessorReader accessors_;
  SoupBuilder builder_;
};

}  // namespace

TriangleSoup read_gltf(std::string_view bytes, const std::string& name, bool require_glb) {
  const tinygltf::Model model = load_model(bytes, name, require_glb);
  return GltfReader(model, name).read();
}

}  // namespace mr::plugins::gltf
