#pragma once
// Builds small glTF files by hand for the glTF tests: a JSON document and a
// binary buffer, packed as GLB or as .gltf with an external .bin. Kept
// deliberately simple so that tests can corrupt any field afterwards.

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace mr::test::gltf {

struct HandBuilt {
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::string bin;

  /// Appends raw bytes (4-aligned) as a bufferView; returns its index.
  int add_view(const void* data, std::size_t size, int target = 0) {
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (target) view["target"] = target;
    bin.append(static_cast<const char*>(data), size);
    doc["bufferViews"].push_back(view);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }

  int add_accessor(nlohmann::json accessor) {
    doc["accessors"].push_back(std::move(accessor));
    return static_cast<int>(doc["accessors"].size()) - 1;
  }

  /// A float accessor of `type` ("VEC3", ...) holding `values`.
  int add_floats(const std::vector<float>& values, const char* type, int components) {
    const int view = add_view(values.data(), values.size() * sizeof(float), 34962);
    nlohmann::json accessor = {
        {"bufferView", view}, {"componentType", 5126}, {"count", values.size() / components}, {"type", type}};
    if (std::string(type) == "VEC3") {  // min/max, as the spec requires for POSITION
      std::vector<float> lo(3, 1e30f), hi(3, -1e30f);
      for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], values[i]);
        hi[i % 3] = std::max(hi[i % 3], values[i]);
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    return add_accessor(accessor);
  }

  int add_indices(const std::vector<std::uint32_t>& indices) {
    const int view = add_view(indices.data(), indices.size() * 4, 34963);
    return add_accessor(
        {{"bufferView", view}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}});
  }

  /// Adds a mesh with one primitive; returns the mesh index.
  int add_mesh(nlohmann::json attributes, int indices = -1, int mode = 4) {
    nlohmann::json primitive = {{"attributes", attributes}, {"mode", mode}};
    if (indices >= 0) primitive["indices"] = indices;
    doc["meshes"].push_back({{"primitives", {primitive}}});
    return static_cast<int>(doc["meshes"].size()) - 1;
  }

  int add_node(nlohmann::json node) {
    doc["nodes"].push_back(std::move(node));
    return static_cast<int>(doc["nodes"].size()) - 1;
  }

  /// One scene holding `roots`, made the default.
  void set_scene(const std::vector<int>& roots) {
    doc["scenes"] = nlohmann::json::array({{{"nodes", roots}}});
    doc["scene"] = 0;
  }

  /// The JSON with buffer 0 described (uri empty for GLB).
  std::string json_text(const std::string& uri = "") const {
    nlohmann::json d = doc;
    if (!bin.empty()) {
      d["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
      if (!uri.empty()) d["buffers"][0]["uri"] = uri;
    }
    return d.dump();
  }

  std::vector<char> glb() const { return pack_glb(json_text(), bin); }

  static std::vector<char> pack_glb(std::string json, std::string binary) {
    json.resize((json.size() + 3) / 4 * 4, ' ');
    binary.resize((binary.size() + 3) / 4 * 4, '\0');
    std::vector<char> out;
    const auto u32 = [&](std::uint32_t v) {
      const char* p = reinterpret_cast<const char*>(&v);
      out.insert(out.end(), p, p + 4);
    };
    const std::size_t total = 12 + 8 + json.size() + (binary.empty() ? 0 : 8 + binary.size());
    u32(0x46546C67);
    u32(2);
    u32(static_cast<std::uint32_t>(total));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534A);
    out.insert(out.end(), json.begin(), json.end());
    if (!binary.empty()) {
      u32(static_cast<std::uint32_t>(binary.size()));
      u32(0x004E4942);
      out.insert(out.end(), binary.begin(), binary.end());
    }
    return out;
  }
};

inline void put_u32(std::vector<char>& bytes, std::size_t offset, std::uint32_t value) {
  std::memcpy(bytes.data() + offset, &value, 4);
}

/// Offset of the BIN chunk header in a GLB built by pack_glb.
inline std::size_t bin_chunk_offset(const std::vector<char>& glb) {
  std::uint32_t json_length;
  std::memcpy(&json_length, glb.data() + 12, 4);
  return 20 + json_length;
}

/// A unit right triangle in z=0, indexed, as a GLB-ready model.
inline HandBuilt one_triangle() {
  HandBuilt model;
  const int positions = model.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  const int indices = model.add_indices({0, 1, 2});
  model.add_mesh({{"POSITION", positions}}, indices);
  model.set_scene({model.add_node({{"mesh", 0}})});
  return model;
}

}  // namespace mr::test::gltf
