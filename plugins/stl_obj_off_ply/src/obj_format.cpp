// OBJ reader. Our own rather than OpenMesh's OBJReader: OpenMesh drops faces
// it cannot add (bad or zero indices) with a note on its global omerr stream
// instead of failing, ignores backslash line continuations, and parses through
// istreams. Here every face is kept and fan-triangulated, and every problem is
// an InputError with its line number.
//
// Choices:
// - Indices refer to elements defined before the face (as the OBJ spec says);
//   negative indices count back from the last one. Index 0 is an error.
// - The positions are the vertex set, kept exactly. A corner's texture
//   coordinate and normal are attributes of its position: where corners of one
//   position carry different ones (a seam) the UVs are averaged and the normals
//   summed and normalized. Positions no corner gives an attribute to get zero.
// - Regions: 'usemtl' names if the file has any, else 'g'/'o' group names.
//   Faces before the first name belong to a region named "default".
// - 'v x y z r g b' colours are kept when every vertex has them.

#include "formats.h"
#include "soup_importer.h"

#include <mr/io/text_cursor.h>

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
    uvs_.emplace_back(static_cast<float>(u), static_cast<float>(v));
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
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
      const Corner corner = parse_corner(token);
      polygon_.push_back(corner.position);
      add_corner_attributes(corner);
    }
    if (polygon_.size() < 3)
      cursor_.fail("face with " + std::to_string(polygon_.size()) + " vertices, needs at least 3");
    append_fan(triangles_, polygon_);
    face_materials_.resize(triangles_.size(), material_);
    face_groups_.resize(triangles_.size(), group_);
  }

  void add_corner_attributes(const Corner& corner) {
    if (corner.uv >= 0) {
      if (uv_sum_.size() <= corner.position) uv_sum_.resize(positions_.size(), Vec3d::Zero());
      uv_sum_[corner.position] += Vec3d(uvs_[corner.uv].x(), uvs_[corner.uv].y(), 1.0);
    }
    if (corner.normal >= 0) {
      if (normal_sum_.size() <= corner.position) normal_sum_.resize(positions_.size(), Vec3d::Zero());
      normal_sum_[corner.position] += normals_[corner.normal].cast<double>();
    }
  }

  static std::vector<std::int32_t> regions_of(const std::vector<std::int32_t>& ids, RegionTable& table) {
    std::vector<std::int32_t> regions(ids.size());
    for (std::size_t f = 0; f < ids.size(); ++f) regions[f] = ids[f] >= 0 ? ids[f] : table.id_of("default");
    return regions;
  }

  TriangleSoup finish() {
    TriangleSoup soup;
    soup.triangles = std::move(triangles_);
    if (has_materials_ || has_groups_) {
      RegionTable& table = has_materials_ ? materials_ : groups_;
      soup.face_regions = regions_of(has_materials_ ? face_materials_ : face_groups_, table);
      soup.region_names = table.names();
    }
    const std::size_t n = positions_.size();
    if (!uv_sum_.empty()) {
      uv_sum_.resize(n, Vec3d::Zero());
      for (const Vec3d& s : uv_sum_)
        soup.uvs.push_back(s.z() > 0
                               ? Vec2f(static_cast<float>(s.x() / s.z()), static_cast<float>(s.y() / s.z()))
                               : Vec2f::Zero());
    }
    if (!normal_sum_.empty()) {
      normal_sum_.resize(n, Vec3d::Zero());
      for (const Vec3d& s : normal_sum_)
        soup.normals.push_back(s.norm() > 0 ? Vec3f(s.normalized().cast<float>()) : Vec3f::Zero());
    }
    if (colors_.size() == n && n > 0) soup.colors = std::move(colors_);
    soup.positions = std::move(positions_);
    return soup;
  }

  io::TextCursor cursor_;
  std::string joined_;
  std::vector<Vec3d> positions_;
  std::vector<Vec2f> uvs_;
  std::vector<Vec3f> normals_;
  std::vector<Vec4f> colors_;
  std::vector<Triangle> triangles_;
  std::vector<Index> polygon_;
  std::vector<Vec3d> uv_sum_;  // (u, v, corner count) per position
  std::vector<Vec3d> normal_sum_;
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
