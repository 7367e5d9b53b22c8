#include <mr/core/triangle_soup.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace mr {
namespace {

template <class T>
void append_attribute(std::vector<T>& mine, const std::vector<T>& theirs, bool keep) {
  if (keep)
    mine.insert(mine.end(), theirs.begin(), theirs.end());
  else
    mine.clear();
}

template <class T>
std::string check_size(const std::vector<T>& attribute, std::size_t expected, const char* name) {
  if (attribute.empty() || attribute.size() == expected) return {};
  return std::string(name) + " has " + std::to_string(attribute.size()) + " entries, expected " +
         std::to_string(expected);
}

}  // namespace

void TriangleSoup::append(const TriangleSoup& other) {
  const bool first = positions.empty() && triangles.empty();
  const auto offset = static_cast<Index>(positions.size());
  const std::size_t old_triangles = triangles.size();
  append_attribute(normals, other.normals, first || (has_normals() && other.has_normals()));
  append_attribute(uvs, other.uvs, first || (has_uvs() && other.has_uvs()));
  append_attribute(colors, other.colors, first || (has_colors() && other.has_colors()));
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  for (const Triangle& t : other.triangles)
    triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});

  if (has_face_regions() || other.has_face_regions()) {
    face_regions.resize(old_triangles, 0);
    if (other.has_face_regions())
      face_regions.insert(face_regions.end(), other.face_regions.begin(), other.face_regions.end());
    else
      face_regions.resize(triangles.size(), 0);
  }
  if (has_face_sources() || other.has_face_sources()) {
    face_sources.resize(old_triangles, -1);
    if (other.has_face_sources())
      face_sources.insert(face_sources.end(), other.face_sources.begin(), other.face_sources.end());
    else
      face_sources.resize(triangles.size(), -1);
  }
  if (region_names.size() < other.region_names.size()) region_names.resize(other.region_names.size());
  for (std::size_t i = 0; i < other.region_names.size(); ++i)
    if (region_names[i].empty()) region_names[i] = other.region_names[i];
  if (materials.empty() && !other.materials.empty()) {
    const int image_offset = static_cast<int>(images.size());
    for (Material m : other.materials) {
      if (m.base_color_image >= 0) m.base_color_image += image_offset;
      materials.push_back(std::move(m));
    }
    images.insert(images.end(), other.images.begin(), other.images.end());
  }
}

std::string find_soup_inconsistency(const TriangleSoup& soup) {
  const std::size_t n = soup.positions.size();
  for (std::size_t v = 0; v < n; ++v)
    if (!soup.positions[v].allFinite())
      return "vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)";
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    for (Index i : soup.triangles[f])
      if (i >= n)
        return "triangle " + std::to_string(f) + " refers to vertex " + std::to_string(i) +
               " but there are only " + std::to_string(n) + " vertices";
  for (const std::string& problem :
       {check_size(soup.normals, n, "normals"), check_size(soup.uvs, n, "texture coordinates"),
        check_size(soup.colors, n, "colors"),
        check_size(soup.face_regions, soup.triangles.size(), "face regions"),
        check_size(soup.face_sources, soup.triangles.size(), "face sources")})
    if (!problem.empty()) return problem;
  for (std::size_t m = 0; m < soup.materials.size(); ++m) {
    const int image = soup.materials[m].base_color_image;
    if (image < -1 || image >= static_cast<int>(soup.images.size()))
      return "material " + std::to_string(m) + " refers to image " + std::to_string(image) +
             " but there are " + std::to_string(soup.images.size()) + " images";
  }
  return {};
}

Eigen::AlignedBox3d bounding_box(const TriangleSoup& soup) {
  if (soup.positions.empty()) return Eigen::AlignedBox3d(Vec3d::Zero(), Vec3d::Zero());
  Eigen::AlignedBox3d box;
  for (const Vec3d& p : soup.positions) box.extend(p);
  return box;
}

std::array<double, 9> sorted_corner_coordinates(const std::array<Vec3d, 3>& corners) {
  std::array<Vec3d, 3> sorted = corners;
  std::sort(sorted.begin(), sorted.end(), [](const Vec3d& a, const Vec3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  std::array<double, 9> key{};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) key[3 * c + k] = sorted[c][k];
  return key;
}

Eigen::AlignedBox3d used_bounding_box(const TriangleSoup& soup) {
  Eigen::AlignedBox3d box;
  for (const Triangle& t : soup.triangles)
    for (Index v : t) box.extend(soup.positions[v]);
  return box;
}

double bounding_box_diagonal(const TriangleSoup& soup) { return bounding_box(soup).diagonal().norm(); }

}  // namespace mr
