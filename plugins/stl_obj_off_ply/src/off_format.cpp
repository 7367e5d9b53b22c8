// OFF reader and writer. Our own reader rather than OpenMesh's OFFReader:
// OpenMesh reserves memory for the vertex and face counts of the header
// before checking them against the file, so a hostile header makes it
// allocate gigabytes, and it reports truncation on its global omerr stream.
// Here the counts are checked against the bytes left before anything is
// reserved, and every problem is an InputError with its line number.
//
// Accepted: [ST][C][N]OFF keywords, '#' comments anywhere, counts on the
// keyword line or the next ones, and counts glued to the keyword ("OFF8 6 12"
// reads as 8 vertices, 6 faces, 12 edges). One vertex and one face a line;
// a face's trailing colour is ignored. Vertex colours are 3 or 4 values,
// integers 0..255 when any value exceeds 1 and none has a decimal point,
// else floats 0..1. Binary OFF and 4D/nD variants are rejected.

#include "formats.h"
#include "soup_importer.h"

#include <mr/io/output_file.h>
#include <mr/io/text_cursor.h>

#include <algorithm>

namespace mr::plugins::stl_obj_off_ply {
namespace {

struct OffHeader {
  bool normals = false, colors = false, uvs = false;
  std::int64_t vertices = 0, faces = 0;
};

std::string_view strip_comment(std::string_view line) { return io::trim(line.substr(0, line.find('#'))); }

class OffParser {
 public:
  OffParser(const std::string& path, std::string_view text) : cursor_(path, text) {}

  TriangleSoup parse() {
    parse_header();
    // The smallest vertex line is "0 0 0\n" (6 bytes), the smallest face "3 0 0 0\n".
    const auto left = static_cast<std::int64_t>(cursor_.remaining());
    if (header_.vertices > left / 6 || header_.faces > left / 8 ||
        header_.vertices * 6 + header_.faces * 8 > left + 2)
      cursor_.fail("the header claims " + std::to_string(header_.vertices) + " vertices and " +
                   std::to_string(header_.faces) + " faces but only " + std::to_string(left) +
                   " bytes follow it");
    soup_.positions.reserve(static_cast<std::size_t>(header_.vertices));
    for (std::int64_t v = 0; v < header_.vertices; ++v) parse_vertex();
    soup_.triangles.reserve(static_cast<std::size_t>(header_.faces));
    for (std::int64_t f = 0; f < header_.faces; ++f) parse_face();
    return std::move(soup_);
  }

 private:
  std::string_view content_line(const char* what) {
    std::string_view line;
    while (cursor_.next_line(line)) {
      line = strip_comment(line);
      if (!line.empty()) return line;
    }
    cursor_.fail(std::string("the file ends before ") + what);
  }

  void parse_header() {
    io::Tokens tokens(content_line("the OFF header"));
    const std::string_view keyword = tokens.next();
    const std::size_t off = keyword.find("OFF");
    if (off == std::string_view::npos)
      cursor_.fail("not an OFF file: the first word is '" + std::string(keyword.substr(0, 40)) + "'");
    const std::string_view prefix = keyword.substr(0, off);
    if (prefix.find_first_not_of("STCN") != std::string_view::npos)
      cursor_.fail("unsupported OFF variant '" + std::string(keyword) + "' (only [ST][C][N]OFF)");
    header_.uvs = prefix.find("ST") != std::string_view::npos;
    header_.colors = prefix.find('C') != std::string_view::npos;
    header_.normals = prefix.find('N') != std::string_view::npos;
    std::vector<std::int64_t> counts;
    const std::string_view glued = keyword.substr(off + 3);
    if (!glued.empty()) {
      std::int64_t count = 0;
      if (!io::parse_integer(glued, count))
        cursor_.fail("unsupported OFF keyword '" + std::string(keyword) + "'");
      counts.push_back(count);
    }
    if (!tokens.empty() && io::iequals(io::Tokens(tokens.rest()).next(), "BINARY"))
      cursor_.fail("binary OFF is not supported");
    while (counts.size() < 2) {
      if (tokens.empty()) tokens = io::Tokens(content_line("the vertex and face counts"));
      counts.push_back(cursor_.integer(tokens, "vertex or face count"));
    }
    header_.vertices = counts[0];
    header_.faces = counts[1];
    if (header_.vertices < 0 || header_.faces < 0) cursor_.fail("negative vertex or face count");
    if (header_.vertices > std::int64_t{0xFFFFFFFF}) cursor_.fail("more than 2^32 vertices");
  }

  void parse_vertex() {
    io::Tokens tokens(content_line("all vertices are read"));
    Vec3d p;
    for (int k = 0; k < 3; ++k) p[k] = cursor_.number(tokens, "vertex coordinate");
    if (!p.allFinite()) cursor_.fail("vertex coordinate is not finite (NaN or Inf)");
    soup_.positions.push_back(p);
    if (header_.normals) {
      Vec3f n;
      for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(cursor_.number(tokens, "vertex normal"));
      soup_.normals.push_back(n);
    }
    std::vector<std::string_view> rest;
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) rest.push_back(token);
    Vec2f uv = Vec2f::Zero();
    if (header_.uvs) {
      if (rest.size() < 2) cursor_.fail("missing texture coordinates");
      for (int k = 0; k < 2; ++k)
        uv[k] = static_cast<float>(number(rest[rest.size() - 2 + k], "texture coordinate"));
      rest.resize(rest.size() - 2);
      soup_.uvs.push_back(uv);
    }
    if (header_.colors) soup_.colors.push_back(parse_color(rest));
  }

  double number(std::string_view token, const char* what) const {
    io::Tokens single(token);
    return cursor_.number(single, what);
  }

  Vec4f parse_color(const std::vector<std::string_view>& tokens) const {
    if (tokens.size() < 3) cursor_.fail("a COFF vertex needs 3 or 4 colour values");
    Vec4f color(0, 0, 0, 1);
    bool integers = true, above_one = false;
    for (std::size_t k = 0; k < std::min<std::size_t>(4, tokens.size()); ++k) {
      color[static_cast<int>(k)] = static_cast<float>(number(tokens[k], "colour value"));
      integers = integers && tokens[k].find_first_of(".eE") == std::string_view::npos;
      above_one = above_one || color[static_cast<int>(k)] > 1.0f;
    }
    if (integers && above_one) {
      color.head<3>() /= 255.0f;
      if (tokens.size() >= 4) color[3] /= 255.0f;
    }
    return color;
  }

  void parse_face() {
    io::Tokens tokens(content_line("all faces are read"));
    const std::int64_t count = cursor_.integer(tokens, "face vertex count");
    if (count < 3) cursor_.fail("face with " + std::to_string(count) + " vertices, needs at least 3");
    if (count > static_cast<std::int64_t>(tokens.rest().size()))
      cursor_.fail("face with fewer indices than its count");
    polygon_.clear();
    for (std::int64_t k = 0; k < count; ++k) {
      const std::int64_t index = cursor_.integer(tokens, "face vertex index");
      if (index < 0 || index >= header_.vertices)
        cursor_.fail("face vertex index " + std::to_string(index) +
                     " out of range: " + std::to_string(header_.vertices) + " vertices");
      polygon_.push_back(static_cast<Index>(index));
    }
    append_fan(soup_.triangles, polygon_);
  }

  io::TextCursor cursor_;
  OffHeader header_;
  TriangleSoup soup_;
  std::vector<Index> polygon_;
};

}  // namespace

TriangleSoup read_off(std::string_view bytes, const std::string& name) {
  return OffParser(name, bytes).parse();
}

void write_off(const TriangleSoup& soup, const std::filesystem::path& path) {
  io::OutputFile out(path);
  out << (soup.has_uvs() ? "ST" : "") << (soup.has_colors() ? "C" : "") << (soup.has_normals() ? "N" : "")
      << "OFF\n";
  out << static_cast<std::int64_t>(soup.num_vertices()) << ' '
      << static_cast<std::int64_t>(soup.num_triangles()) << " 0\n";
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    const Vec3d& p = soup.positions[v];
    out << p.x() << ' ' << p.y() << ' ' << p.z();
    if (soup.has_normals())
      out << ' ' << soup.normals[v].x() << ' ' << soup.normals[v].y() << ' ' << soup.normals[v].z();
    if (soup.has_colors())
      for (int k = 0; k < 4; ++k) out << ' ' << soup.colors[v][k];
    if (soup.has_uvs()) out << ' ' << soup.uvs[v].x() << ' ' << soup.uvs[v].y();
    out << '\n';
  }
  for (const Triangle& t : soup.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  out.close();
}

}  // namespace mr::plugins::stl_obj_off_ply
