#pragma once
// MTL material libraries, the companions of OBJ files: diffuse colour,
// opacity, emission, the PBR extension's roughness and metalness, and the
// diffuse texture (map_Kd), mapped onto mr::Material. Texture images are
// kept encoded; only PNG and JPEG (what glTF carries) are taken.

#include <mr/core/material.h>
#include <mr/core/triangle_soup.h>

#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace mr::plugins::stl_obj_off_ply {

struct MtlLibrary {
  std::map<std::string, Material> materials;  ///< by name
  std::vector<EncodedImage> images;           ///< indexed by Material::base_color_image
};

/// Parses an MTL file's text; texture paths are relative to `path`'s folder.
/// Throws InputError naming `path` on a malformed number. Textures that are
/// missing or neither PNG nor JPEG are left out (the material keeps its colour).
MtlLibrary parse_mtl(std::string_view text, const std::filesystem::path& path);

/// Reads the libraries an OBJ file names (`mtllib`, relative to the OBJ's
/// folder) and gives `soup` one material per region, by region name. Does
/// nothing when no library can be read (OBJ files often travel without theirs).
void attach_mtl_materials(TriangleSoup& soup, const std::vector<std::string>& libraries,
                          const std::filesystem::path& obj_path);

/// Writes `soup`'s materials as `<obj stem>.mtl` beside `obj_path`, with each
/// texture as `<obj stem>_<n>.png|jpg`; returns the library's file name.
std::string write_mtl(const TriangleSoup& soup, const std::filesystem::path& obj_path);

/// The name a region is written under in OBJ and MTL files.
std::string obj_region_name(const TriangleSoup& soup, std::int32_t region);

}  // namespace mr::plugins::stl_obj_off_ply
