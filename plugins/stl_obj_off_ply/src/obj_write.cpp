// OBJ writer. Coordinates are written in the shortest form that reads back as
// the same double (as exact as %.17g, and shorter). A corner's uv and normal
// share its position's index; face regions become 'usemtl' runs in triangle
// order, so the triangle order is kept. Names are written as UTF-8
// (io::as_utf8), one line each. Materials go to an MTL library beside the
// file, named after it, with their textures.

#include "formats.h"
#include "mtl_format.h"

#include <mr/io/output_file.h>
#include <mr/io/text_encoding.h>

namespace mr::plugins::stl_obj_off_ply {
namespace {

void write_vertices(const TriangleSoup& soup, io::OutputFile& out) {
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    const Vec3d& p = soup.positions[v];
    out << "v " << p.x() << ' ' << p.y() << ' ' << p.z();
    if (soup.has_colors())
      out << ' ' << soup.colors[v].x() << ' ' << soup.colors[v].y() << ' ' << soup.colors[v].z();
    out << '\n';
  }
  // OBJ's v runs up from the image's bottom; the soup's (glTF's) runs down.
  // Flipped in double, where 1 - v is exact: the reader's flip gives v back.
  for (const Vec2f& uv : soup.uvs) out << "vt " << uv.x() << ' ' << 1.0 - double(uv.y()) << '\n';
  for (const Vec3f& n : soup.normals) out << "vn " << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
}

void write_corner(const TriangleSoup& soup, io::OutputFile& out, Index v) {
  const std::int64_t one_based = std::int64_t{v} + 1;
  out << ' ' << one_based;
  if (soup.has_uvs() && soup.has_normals())
    out << '/' << one_based << '/' << one_based;
  else if (soup.has_uvs())
    out << '/' << one_based;
  else if (soup.has_normals())
    out << "//" << one_based;
}

}  // namespace

void write_obj(const TriangleSoup& soup, const std::filesystem::path& path,
               const std::filesystem::path& destination) {
  // The library first, so that the OBJ never names a file that is not there.
  const bool materials = !soup.materials.empty() && soup.has_face_regions() && !destination.empty();
  const std::string library = materials ? write_mtl(soup, destination) : std::string();
  io::OutputFile out(path);
  out << "# written by meshrepair\n";
  if (materials) out << "mtllib " << std::string_view(library) << '\n';
  write_vertices(soup, out);
  std::int32_t current_region = -1;
  for (std::size_t f = 0; f < soup.num_triangles(); ++f) {
    if (soup.has_face_regions() && (f == 0 || soup.face_regions[f] != current_region)) {
      current_region = soup.face_regions[f];
      out << "usemtl " << std::string_view(obj_region_name(soup, current_region)) << '\n';
    }
    out << 'f';
    for (Index v : soup.triangles[f]) write_corner(soup, out, v);
    out << '\n';
  }
  out.close();
}

}  // namespace mr::plugins::stl_obj_off_ply
