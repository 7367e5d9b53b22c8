#include "gltf_load.h"

#include "glb_container.h"

#include <mr/core/errors.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string_view>

namespace mr::plugins::gltf {
namespace {

// Deeper JSON than this is rejected before parsing: tinygltf converts
// "extras" and "extensions" recursively, so a hostile nesting depth would
// overflow the stack. Real glTF files nest a dozen levels at most.
constexpr int max_json_depth = 256;

void check_json_depth(std::string_view json, const std::string& path) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > max_json_depth)
        throw InputError(
            path, "invalid glTF: JSON nested more than " + std::to_string(max_json_depth) + " levels deep");
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
}

// File access for external buffers: no shell-style path expansion, regular
// files only (not devices or pipes), and never any writing.
bool file_exists(const std::string& file, void*) {
  std::error_code ec;
  return std::filesystem::is_regular_file(file, ec);
}

std::string expand_nothing(const std::string& file, void*) { return file; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& file, void*) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    *err = "not a regular file";
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  const auto size = std::filesystem::file_size(file, ec);
  if (!in || ec) {
    *err = "cannot open the file";
    return false;
  }
  out->resize(size);
  if (size > 0 && !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    *err = "read error";
    return false;
  }
  return true;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "writing is not allowed while reading";
  return false;
}

// We never need pixels: an image's bytes are kept as the file holds them
// (PNG, JPEG), undecoded, so that a writer can hand them on.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  image->image.assign(bytes, bytes + std::max(size, 0));
  return true;
}

// tinygltf 2.7 rejects a primitive whose index accessor has no bufferView,
// which is exactly how KHR_draco_mesh_compression primitives look. The
// decoded Draco mesh carries its own faces, so the index accessor is dropped.
std::string drop_draco_index_accessors(std::string_view json, const std::string& path) {
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
  if (doc.is_discarded()) throw InputError(path, "invalid JSON: the glTF document cannot be parsed");
  if (!doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array()) return std::string(json);
  for (auto& mesh : doc["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (auto& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("extensions")) continue;
      const auto& extensions = primitive["extensions"];
      if (extensions.is_object() && extensions.contains("KHR_draco_mesh_compression"))
        primitive.erase("indices");
    }
  }
  return doc.dump();
}

std::string trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

tinygltf::Model load_model(std::string_view all, const std::filesystem::path& path, bool require_glb) {
  const std::string name = path.string();
  const bool glb = require_glb || has_glb_magic(all);
  if (all.size() > 0xFFFFFFFFull) throw InputError(name, "glTF files of 4 GB or more are not supported");

  GlbChunks chunks;
  std::string_view json = all;
  if (glb) {
    chunks = split_glb(all, name);
    json = chunks.json;
  }
  check_json_depth(json, name);

  std::vector<char> patched_glb;
  std::string patched_json;
  const bool has_draco = json.find("KHR_draco_mesh_compression") != std::string_view::npos;
  if (has_draco) {
    patched_json = drop_draco_index_accessors(json, name);
    json = patched_json;
    if (glb) patched_glb = replace_glb_json(chunks, json);
  }

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_nothing, &read_whole_file, &refuse_write, nullptr});
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  const std::string base_dir = path.has_parent_path() ? path.parent_path().string() : std::string(".");
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    if (glb) {
      const std::string_view data =
          has_draco ? std::string_view(patched_glb.data(), patched_glb.size()) : chunks.glb;
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn,
                                       reinterpret_cast<const unsigned char*>(data.data()),
                                       static_cast<unsigned int>(data.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                      static_cast<unsigned int>(json.size()), base_dir);
    }
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(name, "invalid JSON: " + library_error_text(e));
  } catch (const std::exception& e) {
    throw InputError(name, "invalid glTF: " + library_error_text(e));
  }
  if (!ok) {
    // tinygltf reports JSON syntax errors as nlohmann's parse_error text.
    const bool syntax = err.find("parse_error") != std::string::npos;
    throw InputError(
        name, (syntax ? "invalid JSON: " : "invalid glTF: ") + (err.empty() ? "unknown error" : trim(err)));
  }
  return model;
}

}  // namespace mr::plugins::gltf
