// OBJ reader. Our own rather than OpenMesh's OBJReader: OpenMesh drops faces
// it cannot add (bad or zero indices) with a note on its global omerr stream
// instead of failing, ignores backslash line continuations, and parses through
// istreams. Here every face is kept and fan-triangulated, and every problem is
// an InputError with its line number.
//
// Choices:
// - Indices refer to elements defined before the face (as the OBJ spec says);
//   negative indices count back from the last one. Index 0 is an error.
// - The positions are kept exactly, vertex i for the i-th 'v'. Where the
//   corners of one position carry different texture coordinates or normals
//   (a seam, a crease), the first combination stays on vertex i and each other
//   one gets a copy of the position appended after the last 'v', as glTF
//   stores seams. Vertices without a texture coordinate or normal get zero.
// - Texture coordinates are turned to glTF's convention (v runs down the
//   image: v' = 1 - v), the soup's, so that textures map alike from any format.
// - Regions: 'usemtl' names if the file has any, else 'g'/'o' group names.
//   Faces before the first name belong to a region named "default". With
//   'usemtl', the 'mtllib' libraries found beside the file give each region
//   its material and texture (mtl_format.h).
// - 'v x y z r g b' colours are kept when every vertex has them.

#include "formats.h"
#include "mtl_format.h"
#include "soup_importer.h"

#include <mr/io/text_cursor.h>

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

namespace mr::plugins::stl_obj_off_ply {
namespace {

struct Corner {
  Index position;
  std::int64_t uv = -1;
  std::int64_t normal = -1;
};

class ObjParser {
 public:
  ObjParser(const std::string& path, std::string_view text) : cursor_(path, text) {}

  TriangleSoup parse() {
    std::string_view line;
    while (next_logical_line(line)) parse_line(line);
    return finish();
  }

 private:
  // Joins lines that end with a backslash.
  bool next_logical_line(std::string_view& line) {
    if (!cursor_.next_line(line)) return false;
    if (!ends_with_backslash(line)) return true;
    joined_.clear();
    do {
      const std::string_view content = io::trim(line);
      joined_.append(content.substr(0, content.size() - 1)).push_back(' ');
      if (!cursor_.next_line(line)) break;
    } while (ends_with_backslash(line));
    if (!ends_with_backslash(line)) joined_.append(line);
    line = joined_;
    return true;
  }

  static bool ends_with_backslash(std::string_view line) {
    line = io::trim(line);
    return !line.empty() && line.back() == '\\';
  }

  void parse_line(std::string_view line) {
    io::Tokens tokens(line);
    const std::string_view keyword = tokens.next();
    if (keyword == "v")
      parse_vertex(tokens);
    else if (keyword == "vt")
      parse_uv(tokens);
    else if (keyword == "vn")
      normals_.emplace_back(read_vector(tokens, "normal").cast<float>());
    else if (keyword == "f")
      parse_face(tokens);
    else if (keyword == "mtllib")
      libraries_.emplace_back(io::trim(tokens.rest()));
    else if (keyword == "usemtl") {
      material_ = materials_.id_of(region_name(tokens));
      has_materials_ = true;
    } else if (keyword == "g" || keyword == "o") {
      group_ = groups_.id_of(region_name(tokens));
      has_groups_ = true;
    }
  }

  static std::string_view region_name(io::Tokens& tokens) {
    const std::string_view name = io::trim(tokens.rest());
    return name.empty() ? "default" : name;
  }

  Vec3d read_vector(io::Tokens& tokens, const char* what) {
    Vec3d v;
    for (int k = 0; k < 3; ++k) v[k] = cursor_.number(tokens, what);
    if (!v.allFinite()) cursor_.fail(std::string(what) + " is not finite (NaN or Inf)");
    return v;
  }

  void parse_uv(io::Tokens& tokens) {
    const double u = cursor_.number(tokens, "texture coordinate");
    const double v = tokens.empty() ? 0.0 : cursor_.number(tokens, "texture coordinate");
    uvs_.emplace_back(u, v);
  }

  void parse_vertex(io::Tokens& tokens) {
    positions_.push_back(read_vector(tokens, "vertex coordinate"));
    double extra[4];
    int count = 0;
    while (count < 4 && !tokens.empty()) extra[count++] = cursor_.number(tokens, "vertex value");
    if (count >= 3) {
      colors_.emplace_back(static_cast<float>(extra[0]), static_cast<float>(extra[1]),
                           static_cast<float>(extra[2]), count == 4 ? static_cast<float>(extra[3]) : 1.0f);
    }
  }

  std::int64_t resolve(std::string_view token, std::size_t defined, const char* what) {
    std::int64_t index = 0;
    if (!io::parse_integer(token, index)) cursor_.fail(io::quoted(token) + " is not a " + what + " index");
    if (index == 0) cursor_.fail(std::string(what) + " index 0 (OBJ indices start at 1)");
    const std::int64_t resolved = index > 0 ? index - 1 : static_cast<std::int64_t>(defined) + index;
    if (resolved < 0 || resolved >= static_cast<std::int64_t>(defined))
      cursor_.fail(std::string(what) + " index " + std::to_string(index) +
                   " out of range: " + std::to_string(defined) + " defined so far");
    return resolved;
  }

  Corner parse_corner(std::string_view token) {
    const std::size_t slash1 = token.find('/');
    Corner corner;
    corner.position = static_cast<Index>(resolve(token.substr(0, slash1), positions_.size(), "vertex"));
    if (slash1 == std::string_view::npos) return corner;
    const std::string_view rest = token.substr(slash1 + 1);
    const std::size_t slash2 = rest.find('/');
    const std::string_view uv = rest.substr(0, slash2);
    if (!uv.empty()) corner.uv = resolve(uv, uvs_.size(), "texture coordinate");
    if (slash2 != std::string_view::npos)
      corner.normal = resolve(rest.substr(slash2 + 1), normals_.size(), "normal");
    return corner;
  }

  void parse_face(io::Tokens& tokens) {
    polygon_.clear();
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next())
      polygon_.push_back(parse_corner(token));
    if (polygon_.size() < 3)
      cursor_.fail("face with " + std::to_string(polygon_.size()) + " vertices, needs at least 3");
    for (std::size_t i = 1; i + 1 < polygon_.size(); ++i)  // a fan, as append_fan
      corners_.insert(corners_.end(), {polygon_[0], polygon_[i], polygon_[i + 1]});
    const std::size_t triangles = corners_.size() / 3;
    face_materials_.resize(triangles, material_);
    face_groups_.resize(triangles, group_);
  }

  static std::vector<std::int32_t> regions_of(const std::vector<std::int32_t>& ids, RegionTable& table) {
    std::vector<std::int32_t> regions(ids.size());
    for (std::size_t f = 0; f < ids.size(); ++f) regions[f] = ids[f] >= 0 ? ids[f] : table.id_of("default");
    return regions;
  }

  TriangleSoup finish() {
    TriangleSoup soup;
    if (has_materials_ || has_groups_) {
      RegionTable& table = has_materials_ ? materials_ : groups_;
      soup.face_regions = regions_of(has_materials_ ? face_materials_ : face_groups_, table);
      soup.region_names = table.names();
    }
    if (colors_.size() == positions_.size() && !positions_.empty()) soup.colors = std::move(colors_);
    soup.positions = std::move(positions_);
    add_vertices_and_triangles(soup);
    if (has_materials_) attach_mtl_materials(soup, libraries_, cursor_.path());
    return soup;
  }

  // Vertex i is position i with the attributes of its first corner; other
  // combinations of attributes at a position get a copy of it (see the top).
  void add_vertices_and_triangles(TriangleSoup& soup) {
    const bool with_uvs =
        std::any_of(corners_.begin(), corners_.end(), [](const Corner& c) { return c.uv >= 0; });
    const bool with_normals =
        std::any_of(corners_.begin(), corners_.end(), [](const Corner& c) { return c.normal >= 0; });
    const std::size_t n = soup.positions.size();
    std::map<std::tuple<Index, std::int64_t, std::int64_t>, Index> copies;
    std::vector<Corner> vertex_corner(n, Corner{kUnset});
    // A corner without a texture coordinate (normal) takes the vertex's.
    const auto agree = [](std::int64_t a, std::int64_t b) { return a == b || a < 0 || b < 0; };
    const auto vertex_of = [&](const Corner& c) -> Index {
      Corner& f = vertex_corner[c.position];
      if (f.position == kUnset) f = c;
      if (agree(f.uv, c.uv) && agree(f.normal, c.normal)) {
        f.uv = std::max(f.uv, c.uv);
        f.normal = std::max(f.normal, c.normal);
        return c.position;
      }
      const auto [it, added] = copies.try_emplace({c.position, c.uv, c.normal}, Index(soup.positions.size()));
      if (added) {
        soup.positions.push_back(soup.positions[c.position]);
        if (soup.has_colors()) soup.colors.push_back(soup.colors[c.position]);
        vertex_corner.push_back(c);
      }
      return it->second;
    };
    soup.triangles.reserve(corners_.size() / 3);
    for (std::size_t i = 0; i < corners_.size(); i += 3)
      soup.triangles.push_back(
          {vertex_of(corners_[i]), vertex_of(corners_[i + 1]), vertex_of(corners_[i + 2])});
    if (with_uvs) {
      for (const Corner& c : vertex_corner)
        soup.uvs.push_back(c.uv >= 0 ? Vec2f(float(uvs_[c.uv].x()), float(1.0 - uvs_[c.uv].y()))
                                     : Vec2f::Zero());
    }
    if (with_normals) {
      for (const Corner& c : vertex_corner) {
        const Vec3f normal = c.normal >= 0 ? normals_[c.normal] : Vec3f::Zero();
        soup.normals.push_back(normal.norm() > 0 ? Vec3f(normal.normalized()) : Vec3f::Zero());
      }
    }
  }

  static constexpr Index kUnset = std::numeric_limits<Index>::max();

  io::TextCursor cursor_;
  std::string joined_;
  std::vector<Vec3d> positions_;
  std::vector<Eigen::Vector2d> uvs_;  // as read: flipped in double, 1 - (1 - v) is v
  std::vector<Vec3f> normals_;
  std::vector<Vec4f> colors_;
  std::vector<Corner> corners_;  // three per triangle
  std::vector<Corner> polygon_;
  std::vector<std::string> libraries_;  // 'mtllib' names
  RegionTable materials_, groups_;
  std::int32_t material_ = -1, group_ = -1;
  bool has_materials_ = false, has_groups_ = false;
  std::vector<std::int32_t> face_materials_, face_groups_;
};

}  // namespace

TriangleSoup read_obj(std::string_view bytes, const std::string& name) {
  return ObjParser(name, bytes).parse();
}

}  // namespace mr::plugins::stl_obj_off_ply
