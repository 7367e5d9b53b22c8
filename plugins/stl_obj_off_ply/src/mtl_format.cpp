#include "mtl_format.h"

#include <mr/core/errors.h>
#include <mr/io/atomic_file.h>
#include <mr/io/file_bytes.h>
#include <mr/io/output_file.h>
#include <mr/io/text_cursor.h>
#include <mr/io/text_encoding.h>

#include <algorithm>
#include <system_error>

namespace mr::plugins::stl_obj_off_ply {
namespace {

std::string mime_type_of(const std::vector<char>& bytes) {
  const auto starts_with = [&](std::string_view magic) {
    return bytes.size() >= magic.size() && std::string_view(bytes.data(), magic.size()) == magic;
  };
  if (starts_with("\x89PNG\r\n\x1a\n")) return "image/png";
  if (starts_with("\xff\xd8\xff")) return "image/jpeg";
  return {};
}

// The file a map_Kd line names: its last token when options (-s 1 1 1, -bm
// 0.5, ...) come first, else the whole rest of the line (names may hold spaces).
std::string_view texture_file(std::string_view rest) {
  rest = io::trim(rest);
  if (rest.empty() || rest.front() != '-') return rest;
  const std::size_t space = rest.find_last_of(" \t");
  return space == std::string_view::npos ? std::string_view{} : rest.substr(space + 1);
}

class MtlParser {
 public:
  MtlParser(std::string_view text, const std::filesystem::path& path)
      : cursor_(path.string(), text), path_(path) {}

  MtlLibrary parse() {
    std::string_view line;
    while (cursor_.next_content_line(line, '#')) parse_line(line);
    return std::move(library_);
  }

 private:
  void parse_line(std::string_view line) {
    io::Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    if (keyword == "newmtl") {
      const std::string name(io::trim(tokens.rest()));
      current_ = &library_.materials[name];
      *current_ = Material{};
      current_->name = name;
      current_->metallic = 0.0f;  // MTL's Phong materials are dielectrics
      return;
    }
    if (!current_) return;
    if (keyword == "Kd") {
      for (int k = 0; k < 3; ++k) current_->base_color[k] = number(tokens, "Kd colour");
    } else if (keyword == "Ke") {
      for (int k = 0; k < 3; ++k) current_->emissive[k] = number(tokens, "Ke colour");
    } else if (keyword == "d") {
      set_opacity(number(tokens, "d (opacity)"));
    } else if (keyword == "Tr") {
      set_opacity(1.0f - number(tokens, "Tr (transparency)"));
    } else if (keyword == "Pr") {
      current_->roughness = number(tokens, "Pr (roughness)");
    } else if (keyword == "Pm") {
      current_->metallic = number(tokens, "Pm (metalness)");
    } else if (keyword == "map_Kd") {
      current_->base_color_image = load_texture(texture_file(tokens.rest()));
    }
  }

  float number(io::Tokens& tokens, const char* what) const {
    return static_cast<float>(std::clamp(cursor_.number(tokens, what), -1e30, 1e30));
  }

  void set_opacity(float opacity) {
    current_->base_color[3] = std::clamp(opacity, 0.0f, 1.0f);
    current_->alpha = opacity < 1.0f ? Material::Alpha::blend : Material::Alpha::opaque;
  }

  // Index of the texture in the library's images (read once per file), or -1.
  int load_texture(std::string_view file) {
    if (file.empty()) return -1;
    const std::filesystem::path texture = path_.parent_path() / std::filesystem::path(std::string(file));
    const auto known = texture_index_.find(texture.string());
    if (known != texture_index_.end()) return known->second;
    int index = -1;
    std::error_code error;
    if (std::filesystem::is_regular_file(texture, error)) {
      std::vector<char> bytes = io::read_file_bytes(texture);
      std::string mime = mime_type_of(bytes);
      if (!mime.empty()) {
        index = static_cast<int>(library_.images.size());
        library_.images.push_back({std::move(mime), std::vector<std::uint8_t>(bytes.begin(), bytes.end())});
      }
    }
    texture_index_[texture.string()] = index;
    return index;
  }

  io::TextCursor cursor_;
  std::filesystem::path path_;
  MtlLibrary library_;
  Material* current_ = nullptr;
  std::map<std::string, int> texture_index_;
};

void write_material(io::OutputFile& out, const TriangleSoup& soup, std::size_t r,
                    const std::vector<std::string>& texture_names) {
  const Material& m = soup.materials[r];
  out << "newmtl " << std::string_view(obj_region_name(soup, std::int32_t(r))) << '\n';
  out << "Kd " << m.base_color[0] << ' ' << m.base_color[1] << ' ' << m.base_color[2] << '\n';
  if (m.base_color[3] < 1.0f) out << "d " << m.base_color[3] << '\n';
  if (m.emissive != std::array<float, 3>{0, 0, 0})
    out << "Ke " << m.emissive[0] << ' ' << m.emissive[1] << ' ' << m.emissive[2] << '\n';
  out << "Pr " << m.roughness << "\nPm " << m.metallic << '\n';
  if (m.base_color_image >= 0 && std::size_t(m.base_color_image) < texture_names.size())
    out << "map_Kd " << std::string_view(texture_names[m.base_color_image]) << '\n';
}

}  // namespace

MtlLibrary parse_mtl(std::string_view text, const std::filesystem::path& path) {
  return MtlParser(text, path).parse();
}

void attach_mtl_materials(TriangleSoup& soup, const std::vector<std::string>& libraries,
                          const std::filesystem::path& obj_path) {
  MtlLibrary merged;
  for (const std::string& name : libraries) {
    const std::filesystem::path path = obj_path.parent_path() / std::filesystem::path(name);
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) continue;
    const std::vector<char> text = io::read_file_bytes(path);
    MtlLibrary library = parse_mtl(std::string_view(text.data(), text.size()), path);
    const int offset = static_cast<int>(merged.images.size());
    for (EncodedImage& image : library.images) merged.images.push_back(std::move(image));
    for (auto& [material_name, material] : library.materials) {
      if (material.base_color_image >= 0) material.base_color_image += offset;
      merged.materials.try_emplace(material_name, std::move(material));
    }
  }
  if (merged.materials.empty() || !soup.has_face_regions()) return;
  soup.materials.clear();
  for (const std::string& region : soup.region_names) {
    const auto it = merged.materials.find(region);
    Material material = it != merged.materials.end() ? it->second : Material{};
    material.name = region;
    if (it == merged.materials.end()) material.metallic = 0.0f;
    soup.materials.push_back(std::move(material));
  }
  soup.images = std::move(merged.images);
}

std::string obj_region_name(const TriangleSoup& soup, std::int32_t region) {
  if (region >= 0 && static_cast<std::size_t>(region) < soup.region_names.size() &&
      !soup.region_names[region].empty()) {
    std::string name = io::as_utf8(soup.region_names[region]);
    for (char& c : name)
      if (c == '\n' || c == '\r') c = ' ';
    return name;
  }
  return "region_" + std::to_string(region);
}

std::string write_mtl(const TriangleSoup& soup, const std::filesystem::path& obj_path) {
  const std::string stem = obj_path.stem().string();
  const std::filesystem::path folder = obj_path.parent_path();
  std::vector<std::string> texture_names;
  for (std::size_t i = 0; i < soup.images.size(); ++i) {
    const EncodedImage& image = soup.images[i];
    texture_names.push_back(stem + "_" + std::to_string(i) +
                            (image.mime_type == "image/jpeg" ? ".jpg" : ".png"));
    io::write_atomically(folder / texture_names.back(), [&](const std::filesystem::path& temp) {
      io::OutputFile file(temp);
      file.write_raw(image.bytes.data(), image.bytes.size());
      file.close();
    });
  }
  const std::string library = stem + ".mtl";
  io::write_atomically(folder / library, [&](const std::filesystem::path& temp) {
    io::OutputFile out(temp);
    out << "# written by meshrepair\n";
    for (std::size_t r = 0; r < soup.materials.size(); ++r) write_material(out, soup, r, texture_names);
    out.close();
  });
  return library;
}

}  // namespace mr::plugins::stl_obj_off_ply
