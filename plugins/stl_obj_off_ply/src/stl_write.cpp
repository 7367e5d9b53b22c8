// STL writer, binary or ASCII. Positions are stored as float32 (all STL can
// hold); facet normals are computed from the triangle, zero when degenerate.

#include "formats.h"

#include <mr/core/errors.h>
#include <mr/io/output_file.h>

#include <bit>
#include <limits>

namespace mr::plugins::stl_obj_off_ply {
namespace {

// Facets are written as whole float arrays, in the host byte order.
static_assert(std::endian::native == std::endian::little, "binary STL is little-endian");

Vec3f facet_normal_of(const TriangleSoup& soup, const Triangle& t) {
  return facet_normal(soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]).cast<float>();
}

void write_binary(const TriangleSoup& soup, io::OutputFile& out) {
  if (soup.num_triangles() > std::numeric_limits<std::uint32_t>::max())
    throw RunError("binary STL cannot hold more than 2^32-1 facets");
  std::string header = "binary STL written by meshrepair";
  header.resize(80, ' ');
  out << std::string_view(header);
  out.write_le(static_cast<std::uint32_t>(soup.num_triangles()));
  for (const Triangle& t : soup.triangles) {
    float facet[12];
    const Vec3f n = facet_normal_of(soup, t);
    for (int k = 0; k < 3; ++k) facet[k] = n[k];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) facet[3 + 3 * c + k] = static_cast<float>(soup.positions[t[c]][k]);
    out.write_raw(facet, sizeof(facet));
    out.write_le(std::uint16_t{0});
  }
}

void write_vector(io::OutputFile& out, const Vec3f& v) {
  out << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
}

void write_ascii(const TriangleSoup& soup, io::OutputFile& out) {
  out << "solid mesh\n";
  for (const Triangle& t : soup.triangles) {
    out << "facet normal ";
    write_vector(out, facet_normal_of(soup, t));
    out << "outer loop\n";
    for (Index v : t) {
      out << "vertex ";
      write_vector(out, soup.positions[v].cast<float>());
    }
    out << "endloop\nendfacet\n";
  }
  out << "endsolid mesh\n";
}

}  // namespace

Vec3d facet_normal(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d n = (b - a).cross(c - a);
  const double length = n.norm();
  if (!(length > 0) || !std::isfinite(length)) return Vec3d::Zero();
  return n / length;
}

void write_stl(const TriangleSoup& soup, const std::filesystem::path& path, bool binary) {
  io::OutputFile out(path);
  if (binary)
    write_binary(soup, out);
  else
    write_ascii(soup, out);
  out.close();
}

}  // namespace mr::plugins::stl_obj_off_ply
