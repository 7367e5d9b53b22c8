#include "gltf_vertex_data.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mr::plugins::gltf {
namespace {

bool usable_normal(const Vec3f& n) { return n.allFinite() && n.norm() > 1e-12f; }

// Area-weighted face normals summed at each vertex: the fallback for bad normals.
std::vector<Vec3d> face_normal_sums(const TriangleSoup& soup) {
  std::vector<Vec3d> sums(soup.positions.size(), Vec3d::Zero());
  for (const Triangle& t : soup.triangles) {
    const Vec3d n =
        (soup.positions[t[1]] - soup.positions[t[0]]).cross(soup.positions[t[2]] - soup.positions[t[0]]);
    for (Index v : t) sums[v] += n;
  }
  return sums;
}

void fix_normals(std::vector<Vec3f>& normals, const TriangleSoup& soup) {
  if (!std::all_of(normals.begin(), normals.end(), usable_normal)) {
    const std::vector<Vec3d> sums = face_normal_sums(soup);
    for (std::size_t i = 0; i < normals.size(); ++i) {
      if (usable_normal(normals[i])) continue;
      const Vec3f fallback = sums[i].cast<float>();
      normals[i] = usable_normal(fallback) ? fallback : Vec3f(0, 0, 1);
    }
  }
  for (Vec3f& n : normals) n = (n.cast<double>().normalized()).cast<float>();
}

}  // namespace

TriangleSoup sanitized_for_gltf(const TriangleSoup& soup) {
  TriangleSoup out = soup;
  fix_normals(out.normals, out);
  for (Vec2f& uv : out.uvs)
    for (int c = 0; c < 2; ++c)
      if (!std::isfinite(uv[c])) uv[c] = 0;
  for (Vec4f& color : out.colors)
    for (int c = 0; c < 4; ++c) color[c] = std::isnan(color[c]) ? 1.0f : std::clamp(color[c], 0.0f, 1.0f);
  return out;
}

FloatArrays float_arrays(const TriangleSoup& soup, const Vec3d& origin) {
  FloatArrays a;
  a.positions.reserve(3 * soup.positions.size());
  a.min.fill(std::numeric_limits<float>::max());
  a.max.fill(std::numeric_limits<float>::lowest());
  for (const Vec3d& p : soup.positions) {
    for (int c = 0; c < 3; ++c) {
      const auto f = static_cast<float>(p[c] - origin[c]);
      if (!std::isfinite(f))
        throw RunError("a coordinate (" + std::to_string(p[c]) + ") does not fit in a glTF float");
      a.positions.push_back(f);
      a.min[static_cast<std::size_t>(c)] = std::min(a.min[static_cast<std::size_t>(c)], f);
      a.max[static_cast<std::size_t>(c)] = std::max(a.max[static_cast<std::size_t>(c)], f);
    }
  }
  for (const Vec3f& n : soup.normals) a.normals.insert(a.normals.end(), {n.x(), n.y(), n.z()});
  for (const Vec2f& uv : soup.uvs) a.uvs.insert(a.uvs.end(), {uv.x(), uv.y()});
  for (const Vec4f& c : soup.colors) a.colors.insert(a.colors.end(), {c[0], c[1], c[2], c[3]});
  if (soup.has_face_sources()) {
    a.sources.assign(soup.num_vertices(), -1.0f);
    for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
      const std::int64_t source = soup.face_sources[f];
      if (source < -1 || source > (std::int64_t{1} << 24))
        throw RunError("face source " + std::to_string(source) +
                       " does not fit exactly in the glTF float of " + kSourceFaceAttribute);
      for (Index v : soup.triangles[f]) a.sources[v] = static_cast<float>(source);
    }
  }
  return a;
}

TriangleSoup with_own_vertices(const TriangleSoup& soup) {
  TriangleSoup out = soup;
  out.positions.clear();
  out.normals.clear();
  out.uvs.clear();
  out.colors.clear();
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    Triangle& t = out.triangles[f];
    for (Index& v : t) {
      const Index own = static_cast<Index>(out.positions.size());
      out.positions.push_back(soup.positions[v]);
      if (soup.has_normals()) out.normals.push_back(soup.normals[v]);
      if (soup.has_uvs()) out.uvs.push_back(soup.uvs[v]);
      if (soup.has_colors()) out.colors.push_back(soup.colors[v]);
      v = own;
    }
  }
  return out;
}

std::vector<RegionGroup> group_by_region(const TriangleSoup& soup) {
  if (!soup.has_face_regions()) return {RegionGroup{-1, soup.triangles}};
  std::map<int, std::vector<Triangle>> groups;
  for (std::size_t f = 0; f < soup.triangles.size(); ++f)
    groups[std::max(soup.face_regions[f], -1)].push_back(soup.triangles[f]);
  std::vector<RegionGroup> result;
  for (auto& [region, triangles] : groups) result.push_back({region, std::move(triangles)});
  return result;
}

TriangleSoup sub_soup(const TriangleSoup& soup, const std::vector<Triangle>& triangles) {
  TriangleSoup out;
  constexpr Index unused = std::numeric_limits<Index>::max();
  std::vector<Index> renumber(soup.positions.size(), unused);
  for (Triangle t : triangles) {
    for (Index& v : t) {
      if (renumber[v] == unused) {
        renumber[v] = static_cast<Index>(out.positions.size());
        out.positions.push_back(soup.positions[v]);
        if (soup.has_normals()) out.normals.push_back(soup.normals[v]);
        if (soup.has_uvs()) out.uvs.push_back(soup.uvs[v]);
        if (soup.has_colors()) out.colors.push_back(soup.colors[v]);
      }
      v = renumber[v];
    }
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace mr::plugins::gltf
