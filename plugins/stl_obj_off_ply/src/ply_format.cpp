// PLY reader. Our own rather than OpenMesh's PLYReader: OpenMesh reserves
// memory for the header's counts before checking them against the file,
// reads positions as float (double-precision files lose bits), stops
// silently at a truncated body and reports success, and does not know
// 'tristrips' elements. Here every element count is checked against the bytes
// left before anything is reserved, a truncated body or an out-of-range index
// is an InputError, double positions stay exact, and tristrips (vertex
// indices with -1 restarts) become triangles with alternating orientation.
//
// Read: vertex x y z, normals nx ny nz, texture coordinates (s t, u v,
// texture_u texture_v, texture_s texture_t), colours (red green blue
// [alpha], integer types scaled to [0,1], floats as they are); face
// vertex_indices (or vertex_index) fan-triangulated, and an int 'region'
// face property with names from "comment region <id> <name>" lines. Other
// elements and properties are skipped.

#include "formats.h"
#include "ply_header.h"
#include "ply_source.h"
#include "soup_importer.h"

#include <array>

namespace mr::plugins::stl_obj_off_ply {
namespace {

enum Role { x, y, z, nx, ny, nz, u, v, red, green, blue, alpha, role_count };

constexpr std::array<std::pair<const char*, Role>, 22> kRoleNames{{
    {"x", x},
    {"y", y},
    {"z", z},
    {"nx", nx},
    {"ny", ny},
    {"nz", nz},
    {"s", u},
    {"t", v},
    {"u", u},
    {"v", v},
    {"texture_u", u},
    {"texture_v", v},
    {"texture_s", u},
    {"texture_t", v},
    {"red", red},
    {"green", green},
    {"blue", blue},
    {"alpha", alpha},
    {"diffuse_red", red},
    {"diffuse_green", green},
    {"diffuse_blue", blue},
    {"diffuse_alpha", alpha},
}};

int role_of(const std::string& name) {
  for (const auto& [text, role] : kRoleNames)
    if (name == text) return role;
  return -1;
}

double color_scale(PlyType type) {
  switch (type) {
    case PlyType::uint8:
      return 1.0 / 255.0;
    case PlyType::uint16:
      return 1.0 / 65535.0;
    case PlyType::uint32:
      return 1.0 / 4294967295.0;
    default:
      return 1.0;
  }
}

template <class Source>
class PlyBodyReader {
 public:
  PlyBodyReader(const PlyHeader& header, Source& source) : header_(header), source_(source) {}

  TriangleSoup read() {
    for (const PlyElement& element : header_.elements) {
      source_.check_count(element);
      if (element.name == "vertex")
        read_vertices(element);
      else if (element.name == "face")
        read_faces(element, false);
      else if (element.name == "tristrips")
        read_faces(element, true);
      else
        skip_element(element);
    }
    check_indices();
    if (!soup_.face_regions.empty()) soup_.region_names = header_.region_names;
    return std::move(soup_);
  }

 private:
  void read_vertices(const PlyElement& element) {
    std::vector<int> roles;
    bool has[role_count] = {};
    for (const PlyProperty& p : element.properties) {
      roles.push_back(p.is_list ? -1 : role_of(p.name));
      if (roles.back() >= 0) has[roles.back()] = true;
    }
    if (!has[x] || !has[y] || !has[z]) source_.fail("the vertex element lacks x, y or z");
    const bool normals = has[nx] && has[ny] && has[nz], uvs = has[u] && has[v];
    const bool colors = has[red] && has[green] && has[blue];
    const auto n = static_cast<std::size_t>(element.count);
    soup_.positions.reserve(n);
    if (normals) soup_.normals.reserve(n);
    if (uvs) soup_.uvs.reserve(n);
    if (colors) soup_.colors.reserve(n);
    double value[role_count];
    for (std::size_t i = 0; i < n; ++i) {
      std::fill(std::begin(value), std::end(value), 0.0);
      value[alpha] = 1.0;
      for (std::size_t k = 0; k < roles.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        if (roles[k] < 0) {
          skip_property(p);
          continue;
        }
        const double raw = source_.number(p.type);
        value[roles[k]] = roles[k] >= red ? raw * color_scale(p.type) : raw;
      }
      soup_.positions.emplace_back(value[x], value[y], value[z]);
      if (normals) soup_.normals.emplace_back(float(value[nx]), float(value[ny]), float(value[nz]));
      if (uvs) soup_.uvs.emplace_back(float(value[u]), float(value[v]));
      if (colors)
        soup_.colors.emplace_back(float(value[red]), float(value[green]), float(value[blue]),
                                  float(value[alpha]));
    }
  }

  void read_faces(const PlyElement& element, bool strips) {
    int indices = element.find("vertex_indices");
    if (indices < 0) indices = element.find("vertex_index");
    if (indices < 0 || !element.properties[indices].is_list)
      source_.fail("element '" + element.name + "' has no vertex_indices list");
    const int region = strips ? -1 : element.find("region");
    const bool has_region = region >= 0 && !element.properties[region].is_list;
    for (std::uint64_t f = 0; f < element.count; ++f) {
      std::int32_t face_region = 0;
      for (int k = 0; k < static_cast<int>(element.properties.size()); ++k) {
        const PlyProperty& p = element.properties[k];
        if (k == indices)
          read_index_list(p);
        else if (k == region && has_region)
          face_region = static_cast<std::int32_t>(source_.integer(p.type));
        else
          skip_property(p);
      }
      if (strips)
        append_strips();
      else
        append_polygon(f);
      if (has_region) soup_.face_regions.resize(soup_.triangles.size(), face_region);
    }
  }

  void read_index_list(const PlyProperty& p) {
    const std::int64_t count = source_.list_count(p);
    list_.clear();
    for (std::int64_t i = 0; i < count; ++i) list_.push_back(source_.integer(p.type));
  }

  void append_polygon(std::uint64_t face) {
    if (list_.size() < 3)
      source_.fail("face " + std::to_string(face) + " has " + std::to_string(list_.size()) +
                   " vertices, needs at least 3");
    polygon_.clear();
    for (std::int64_t index : list_) polygon_.push_back(to_index(index));
    append_fan(soup_.triangles, polygon_);
  }

  void append_strips() {
    polygon_.clear();
    for (std::int64_t index : list_) {
      if (index == -1) {
        append_strip(soup_.triangles, polygon_);
        polygon_.clear();
      } else {
        polygon_.push_back(to_index(index));
      }
    }
    append_strip(soup_.triangles, polygon_);
  }

  Index to_index(std::int64_t index) {
    if (index < 0 || index > std::int64_t{0xFFFFFFFF})
      source_.fail("vertex index " + std::to_string(index) + " out of range");
    return static_cast<Index>(index);
  }

  void check_indices() const {
    const std::size_t n = soup_.positions.size();
    for (std::size_t f = 0; f < soup_.triangles.size(); ++f)
      for (Index i : soup_.triangles[f])
        if (i >= n)
          source_.fail("a face refers to vertex " + std::to_string(i) + " but there are only " +
                       std::to_string(n) + " vertices");
  }

  void skip_property(const PlyProperty& p) {
    const std::int64_t count = p.is_list ? source_.list_count(p) : 1;
    source_.skip(p.type, count);
  }

  void skip_element(const PlyElement& element) {
    if (element.properties.empty()) return;
    for (std::uint64_t i = 0; i < element.count; ++i)
      for (const PlyProperty& p : element.properties) skip_property(p);
  }

  const PlyHeader& header_;
  Source& source_;
  TriangleSoup soup_;
  std::vector<std::int64_t> list_;
  std::vector<Index> polygon_;
};

template <class Source>
TriangleSoup read_body(const PlyHeader& header, Source source) {
  return PlyBodyReader<Source>(header, source).read();
}

}  // namespace

TriangleSoup read_ply(std::string_view bytes, const std::string& name) {
  const PlyHeader header = parse_ply_header(name, bytes);
  const char* body = bytes.data() + header.body_offset;
  const std::size_t size = bytes.size() - header.body_offset;
  switch (header.encoding) {
    case PlyEncoding::ascii:
      return read_body(header, PlyAsciiSource(name, body, size));
    case PlyEncoding::binary_little_endian:
      return read_body(header, PlyBinarySource(name, body, size, false));
    case PlyEncoding::binary_big_endian:
      return read_body(header, PlyBinarySource(name, body, size, true));
  }
  throw InputError(name, "unknown PLY encoding");
}

}  // namespace mr::plugins::stl_obj_off_ply
