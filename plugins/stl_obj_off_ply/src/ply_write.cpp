// PLY writer: binary little endian by default, ASCII on request. Positions
// are double so they read back exactly; normals (nx ny nz) and texture
// coordinates (s t) float; colours uchar red green blue alpha; a face region
// is an int 'region' face property with names in "comment region" lines
// (UTF-8, io::as_utf8).

#include "formats.h"

#include <mr/core/errors.h>
#include <mr/io/output_file.h>
#include <mr/io/text_encoding.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::plugins::stl_obj_off_ply {
namespace {

std::uint8_t to_byte(float channel) {
  const float clamped = std::clamp(std::isfinite(channel) ? channel : 0.0f, 0.0f, 1.0f);
  return static_cast<std::uint8_t>(std::lround(clamped * 255.0f));
}

// A region name as one UTF-8 line.
std::string one_line(std::string_view name) {
  std::string text = io::as_utf8(name);
  std::replace_if(
      text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return text;
}

void write_header(const TriangleSoup& soup, io::OutputFile& out, bool binary) {
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n";
  out << "comment written by meshrepair\n";
  for (std::size_t r = 0; r < soup.region_names.size(); ++r)
    out << "comment region " << static_cast<std::int64_t>(r) << ' '
        << std::string_view(one_line(soup.region_names[r])) << '\n';
  out << "element vertex " << static_cast<std::int64_t>(soup.num_vertices()) << '\n';
  out << "property double x\nproperty double y\nproperty double z\n";
  if (soup.has_normals()) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (soup.has_uvs()) out << "property float s\nproperty float t\n";
  if (soup.has_colors())
    out << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n";
  out << "element face " << static_cast<std::int64_t>(soup.num_triangles()) << '\n';
  out << "property list uchar int vertex_indices\n";
  if (soup.has_face_regions()) out << "property int region\n";
  out << "end_header\n";
}

void write_binary_body(const TriangleSoup& soup, io::OutputFile& out) {
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) out.write_le(soup.positions[v][k]);
    if (soup.has_normals())
      for (int k = 0; k < 3; ++k) out.write_le(soup.normals[v][k]);
    if (soup.has_uvs())
      for (int k = 0; k < 2; ++k) out.write_le(soup.uvs[v][k]);
    if (soup.has_colors())
      for (int k = 0; k < 4; ++k) out.write_le(to_byte(soup.colors[v][k]));
  }
  for (std::size_t f = 0; f < soup.num_triangles(); ++f) {
    out.write_le(std::uint8_t{3});
    for (Index i : soup.triangles[f]) out.write_le(static_cast<std::int32_t>(i));
    if (soup.has_face_regions()) out.write_le(soup.face_regions[f]);
  }
}

void write_ascii_body(const TriangleSoup& soup, io::OutputFile& out) {
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    out << soup.positions[v].x() << ' ' << soup.positions[v].y() << ' ' << soup.positions[v].z();
    if (soup.has_normals())
      for (int k = 0; k < 3; ++k) out << ' ' << soup.normals[v][k];
    if (soup.has_uvs())
      for (int k = 0; k < 2; ++k) out << ' ' << soup.uvs[v][k];
    if (soup.has_colors())
      for (int k = 0; k < 4; ++k) out << ' ' << static_cast<int>(to_byte(soup.colors[v][k]));
    out << '\n';
  }
  for (std::size_t f = 0; f < soup.num_triangles(); ++f) {
    const Triangle& t = soup.triangles[f];
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2];
    if (soup.has_face_regions()) out << ' ' << soup.face_regions[f];
    out << '\n';
  }
}

}  // namespace

void write_ply(const TriangleSoup& soup, const std::filesystem::path& path, bool binary) {
  if (soup.num_vertices() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw RunError("PLY with int indices cannot hold more than 2^31-1 vertices");
  io::OutputFile out(path);
  write_header(soup, out, binary);
  if (binary)
    write_binary_body(soup, out);
  else
    write_ascii_body(soup, out);
  out.close();
}

}  // namespace mr::plugins::stl_obj_off_ply
