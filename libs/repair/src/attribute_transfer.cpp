#include <mr/repair/attribute_transfer.h>

#include <mr/core/errors.h>
#include <mr/core/union_find.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/spatial/triangle_distance.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace mr::repair {
namespace {

// Where on an input triangle a corner takes its attributes from.
struct Anchor {
  std::uint32_t triangle = 0;
  std::array<double, 3> weights{1.0, 0.0, 0.0};
};

// Barycentric weights of p's closest point on triangle `t` of `input`;
// exactly one corner's when p is that corner on the grid.
Anchor anchor_on(const TriangleSoup& input, std::uint32_t t, const Vec3d& p, const CoordinateGrid& grid) {
  const std::array<Vec3d, 3> c = input.corners(t);
  for (int i = 0; i < 3; ++i)
    if (grid.nearest(c[i]) == p) {
      Anchor exact{t, {0.0, 0.0, 0.0}};
      exact.weights[i] = 1.0;
      return exact;
    }
  const Vec3d q = spatial::closest_on_triangle(p, c[0], c[1], c[2]).point;
  const Vec3d n = (c[1] - c[0]).cross(c[2] - c[0]);
  const double area = n.squaredNorm();
  if (!(area > 0.0)) return {t, {1.0, 0.0, 0.0}};              // a degenerate source: its first corner
  const double w1 = (c[2] - q).cross(c[0] - q).dot(n) / area;  // the sub-triangle q, c2, c0
  const double w2 = (c[0] - q).cross(c[1] - q).dot(n) / area;
  const double w0 = std::clamp(1.0 - w1 - w2, 0.0, 1.0);
  return {t, {w0, std::clamp(w1, 0.0, 1.0), std::clamp(w2, 0.0, 1.0)}};
}

template <class V>
V blend(const std::vector<V>& values, const Triangle& t, const std::array<double, 3>& w) {
  using Scalar = typename V::Scalar;
  return values[t[0]] * static_cast<Scalar>(w[0]) + values[t[1]] * static_cast<Scalar>(w[1]) +
         values[t[2]] * static_cast<Scalar>(w[2]);
}

// One output vertex: a position and the attributes interpolated there.
struct CornerValues {
  Index position = 0;
  Vec3f normal = Vec3f::Zero();
  Vec2f uv = Vec2f::Zero();
  Vec4f color = Vec4f::Zero();

  auto key() const {
    return std::make_tuple(position, normal.x(), normal.y(), normal.z(), uv.x(), uv.y(), color.x(), color.y(),
                           color.z(), color.w());
  }
};

CornerValues values_at(const TriangleSoup& input, Index position, const Anchor& a) {
  CornerValues v;
  v.position = position;
  const Triangle& t = input.triangles[a.triangle];
  if (input.has_normals()) {
    v.normal = blend(input.normals, t, a.weights);
    if (v.normal.norm() > 0.0f) v.normal.normalize();
  }
  if (input.has_uvs()) v.uv = blend(input.uvs, t, a.weights);
  if (input.has_colors()) v.color = blend(input.colors, t, a.weights);
  return v;
}

void check_sources(const TriangleSoup& surface, const TriangleSoup& input,
                   std::span<const std::int64_t> source) {
  if (source.size() != surface.triangles.size())
    throw UsageError("attribute transfer: " + std::to_string(source.size()) + " sources for " +
                     std::to_string(surface.triangles.size()) + " faces");
  for (std::int64_t s : source)
    if (s < -1 || s >= static_cast<std::int64_t>(input.triangles.size()))
      throw UsageError("attribute transfer: source face " + std::to_string(s) + " is not an input triangle");
}

// Regions: the source's, "filled" for filled faces (a new region), and
// region 0 "input" for the rest when the input had none.
void assign_regions(const TriangleSoup& input, std::span<const std::int64_t> source, TriangleSoup& out) {
  const bool any_filled = std::find(source.begin(), source.end(), -1) != source.end();
  if (!input.has_face_regions() && !any_filled) return;
  std::int32_t filled = 1;
  if (input.has_face_regions()) {
    out.region_names = input.region_names;
    out.materials = input.materials;
    out.images = input.images;
    const std::int32_t largest = *std::max_element(input.face_regions.begin(), input.face_regions.end());
    filled = std::max<std::int32_t>(largest + 1, static_cast<std::int32_t>(out.region_names.size()));
  } else {
    out.region_names = {"input"};
  }
  if (any_filled) {
    out.region_names.resize(static_cast<std::size_t>(filled));
    out.region_names.push_back("filled");
  }
  out.face_regions.resize(source.size());
  for (std::size_t f = 0; f < source.size(); ++f)
    out.face_regions[f] = source[f] < 0              ? filled
                          : input.has_face_regions() ? input.face_regions[static_cast<std::size_t>(source[f])]
                                                     : 0;
}

// Per input triangle, its chart: triangles joined through shared vertices
// (as the input's indices say, not by position), over which the attributes
// vary continuously. A seam or a part boundary separates charts.
std::vector<std::uint32_t> attribute_charts(const TriangleSoup& input) {
  UnionFind vertices(input.positions.size());
  for (const Triangle& t : input.triangles) vertices.unite(t[0], t[1]), vertices.unite(t[0], t[2]);
  std::vector<std::uint32_t> chart(input.triangles.size());
  for (std::size_t f = 0; f < chart.size(); ++f)
    chart[f] = static_cast<std::uint32_t>(vertices.find(input.triangles[f][0]));
  return chart;
}

// The input triangle a corner takes its attributes from: its face's source
// when the corner is one of the source's corners (a kept face: exact);
// else, of the input triangles nearest to it (ties within a hair, as on an
// edge between two) and on the source's chart, the one facing most like
// the corner's face, so that on either side of a crease or a UV seam a face
// reads its own side; the source itself when no triangle of its chart is
// that near. A face's three corners thus read one chart: a face that the
// clean-up stretched across a seam (a decal's border strip merged with the
// panel under it) would otherwise blend texture coordinates from both
// sides into a streak across the atlas. Filled faces (no source) read
// whatever is nearest.
std::uint32_t anchor_triangle(const spatial::AabbTree& tree, const TriangleSoup& input,
                              std::span<const std::uint32_t> chart, const Vec3d& p, const Vec3d& face_normal,
                              std::int64_t source, const CoordinateGrid& grid, double hair) {
  if (source >= 0) {
    const std::array<Vec3d, 3> c = input.corners(static_cast<std::size_t>(source));
    for (const Vec3d& q : c)
      if (grid.nearest(q) == p) return static_cast<std::uint32_t>(source);
  }
  const spatial::ClosestHit nearest = tree.closest(p);
  std::uint32_t best = source >= 0 ? static_cast<std::uint32_t>(source) : nearest.triangle;
  double best_alignment = -2.0;
  for (std::uint32_t t : tree.triangles_within(p, std::sqrt(nearest.squared_distance) + hair)) {
    if (source >= 0 && chart[t] != chart[static_cast<std::size_t>(source)]) continue;
    const std::array<Vec3d, 3> c = input.corners(t);
    const Vec3d n = (c[1] - c[0]).cross(c[2] - c[0]);
    const double alignment = n.norm() > 0.0 ? n.normalized().dot(face_normal) : -1.0;
    if (alignment > best_alignment) best = t, best_alignment = alignment;
  }
  return best;
}

}  // namespace

TriangleSoup with_input_attributes(const TriangleSoup& surface, const TriangleSoup& input,
                                   std::span<const std::int64_t> source, const CoordinateGrid& grid) {
  check_sources(surface, input, source);
  TriangleSoup out;
  out.triangles = surface.triangles;
  assign_regions(input, source, out);
  const bool attributes = input.has_normals() || input.has_uvs() || input.has_colors();
  if (!attributes) {
    out.positions = surface.positions;
    return out;
  }
  const spatial::AabbTree tree(input);
  const std::vector<std::uint32_t> chart = attribute_charts(input);
  const double hair = 1e-9 * bounding_box_diagonal(input);
  std::vector<CornerValues> values(3 * surface.triangles.size());
  tbb::parallel_for(std::size_t(0), surface.triangles.size(), [&](std::size_t f) {
    const std::array<Vec3d, 3> c = surface.corners(f);
    const Vec3d n = (c[1] - c[0]).cross(c[2] - c[0]);
    const Vec3d normal = n.norm() > 0.0 ? Vec3d(n.normalized()) : Vec3d::Zero();
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t from = anchor_triangle(tree, input, chart, c[i], normal, source[f], grid, hair);
      values[3 * f + i] = values_at(input, surface.triangles[f][i], anchor_on(input, from, c[i], grid));
    }
  });
  // One vertex per distinct (position, attributes), in first-use order.
  std::map<decltype(values[0].key()), Index> vertex_of;
  for (std::size_t f = 0; f < surface.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const CornerValues& c = values[3 * f + i];
      const auto [it, added] = vertex_of.emplace(c.key(), static_cast<Index>(out.positions.size()));
      if (added) {
        out.positions.push_back(surface.positions[c.position]);
        if (input.has_normals()) out.normals.push_back(c.normal);
        if (input.has_uvs()) out.uvs.push_back(c.uv);
        if (input.has_colors()) out.colors.push_back(c.color);
      }
      out.triangles[f][i] = it->second;
    }
  return out;
}

}  // namespace mr::repair
