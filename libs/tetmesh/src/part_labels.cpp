#include "part_labels.h"
#include "regions.h"

#include <mr/core/errors.h>
#include <mr/core/union_find.h>
#include <mr/core/weld.h>
#include <mr/tetmesh/winding_filter.h>
#include <mr/winding_number/winding_number.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::tetmesh::detail {
namespace {

// The input's faces grouped into parts: part[f] in 0..labels.size()-1, and
// the tet label of each part.
struct InputParts {
  std::vector<std::uint32_t> part;
  std::vector<std::int32_t> labels;
  std::map<std::int32_t, std::string> names;
};

// The distinct face region ids of `input`, ascending.
std::vector<std::int32_t> region_ids(const TriangleSoup& input) {
  std::vector<std::int32_t> ids = input.face_regions;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

// Parts by face region: label = region id + 1, named by the region's name.
InputParts parts_by_region(const TriangleSoup& input) {
  InputParts parts;
  const std::vector<std::int32_t> ids = region_ids(input);
  for (const std::int32_t id : ids) {
    parts.labels.push_back(id + 1);
    if (id >= 0 && std::size_t(id) < input.region_names.size() && !input.region_names[id].empty())
      parts.names[id + 1] = input.region_names[id];
  }
  parts.part.reserve(input.triangles.size());
  for (const std::int32_t id : input.face_regions)
    parts.part.push_back(std::uint32_t(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()));
  return parts;
}

// Parts by connected component (faces sharing a position), numbered 1, 2,
// ... in order of their first face.
InputParts parts_by_component(const TriangleSoup& input) {
  const TriangleSoup welded = weld_identical_vertices(input);
  UnionFind components(welded.positions.size());
  for (const Triangle& t : welded.triangles) {
    components.unite(t[0], t[1]);
    components.unite(t[0], t[2]);
  }
  InputParts parts;
  std::map<std::size_t, std::uint32_t> part_of_root;
  for (const Triangle& t : welded.triangles) {
    const auto [it, added] =
        part_of_root.try_emplace(components.find(t[0]), std::uint32_t(parts.labels.size()));
    if (added) parts.labels.push_back(std::int32_t(parts.labels.size()) + 1);
    parts.part.push_back(it->second);
  }
  return parts;
}

// Each part's faces as a soup of its own, with only the vertices it uses.
std::vector<TriangleSoup> soups_of_parts(const TriangleSoup& input, const InputParts& parts) {
  std::vector<TriangleSoup> soups(parts.labels.size());
  std::vector<Index> used;  // input vertices of the current part
  std::vector<Index> index_in_part(input.positions.size(), kNoVertex);
  std::vector<std::vector<std::size_t>> faces(parts.labels.size());
  for (std::size_t f = 0; f < input.triangles.size(); ++f) faces[parts.part[f]].push_back(f);
  for (std::size_t p = 0; p < faces.size(); ++p) {
    TriangleSoup& soup = soups[p];
    for (const std::size_t f : faces[p]) {
      Triangle t = input.triangles[f];
      for (Index& v : t) {
        if (index_in_part[v] == kNoVertex) {
          index_in_part[v] = Index(soup.positions.size());
          soup.positions.push_back(input.positions[v]);
          used.push_back(v);
        }
        v = index_in_part[v];
      }
      soup.triangles.push_back(t);
    }
    for (const Index v : used) index_in_part[v] = kNoVertex;
    used.clear();
  }
  return soups;
}

// Per region of tets with kept ones (region_labels' numbering), its
// largest kept tet; kNoTet for regions without.
std::vector<Index> largest_kept_tets(const Mesh& mesh, std::span<const char> keep,
                                     std::span<const std::int32_t> regions) {
  const std::int32_t count = regions.empty() ? 0 : *std::max_element(regions.begin(), regions.end());
  std::vector<Index> largest(std::size_t(count) + 1, kNoTet);
  std::vector<double> volume(largest.size(), -1.0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!keep[t]) continue;
    const double v = tet_approx_volume6(mesh, t);
    if (v > volume[regions[t]]) {
      volume[regions[t]] = v;
      largest[regions[t]] = t;
    }
  }
  return largest;
}

double insideness(double winding, WindingRule rule) {
  return rule == WindingRule::absolute ? std::abs(winding) : winding;
}

// Volume a part's faces enclose (divergence theorem; approximate for open parts).
double enclosed_volume(const TriangleSoup& soup) {
  double six_volume = 0.0;
  for (const Triangle& t : soup.triangles)
    six_volume += soup.positions[t[0]].dot(soup.positions[t[1]].cross(soup.positions[t[2]]));
  return std::abs(six_volume) / 6.0;
}

// Per query point, the label of the innermost part containing it (winding
// number above 1/2, least enclosed volume: an inclusion modelled as a
// closed surface inside another wins over its host), or where none does,
// of the part whose winding number is largest. Ties go to the first part.
std::vector<std::int32_t> label_points(const TriangleSoup& input, const InputParts& parts,
                                       std::span<const Vec3d> points, WindingRule rule) {
  constexpr double kOutside = std::numeric_limits<double>::infinity();
  std::vector<std::int32_t> labels(points.size(), parts.labels.empty() ? 1 : parts.labels.front());
  std::vector<double> best_winding(points.size(), -kOutside);
  std::vector<double> best_volume(points.size(), kOutside);  // of the innermost part containing the point
  const std::vector<TriangleSoup> soups = soups_of_parts(input, parts);
  for (std::uint32_t p = 0; p < parts.labels.size(); ++p) {
    const std::vector<double> winding = WindingNumberTree(soups[p]).evaluate(points);
    const double volume = enclosed_volume(soups[p]);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double w = insideness(winding[i], rule);
      const bool better =
          w > 0.5 ? volume < best_volume[i] : best_volume[i] == kOutside && w > best_winding[i];
      if (better) labels[i] = parts.labels[p];
      if (w > 0.5) best_volume[i] = std::min(best_volume[i], volume);
      best_winding[i] = std::max(best_winding[i], w);
    }
  }
  return labels;
}

std::vector<std::int32_t> label_points_by_winding(const TriangleSoup& input, std::span<const Vec3d> points,
                                                  WindingRule rule) {
  const std::vector<double> winding = WindingNumberTree(input).evaluate(points);
  std::vector<std::int32_t> labels;
  for (const double w : winding)
    labels.push_back(
        std::max<std::int32_t>(1, std::int32_t(std::lround(std::min(insideness(w, rule), 1e6)))));
  return labels;
}

TetLabels resolve(TetLabels mode, const TriangleSoup& input) {
  if (mode != TetLabels::automatic) return mode;
  const std::size_t regions = region_ids(input).size();
  return regions >= 2 && regions <= kMaxLabelledParts ? TetLabels::parts : TetLabels::none;
}

}  // namespace

PartLabels part_labels(const Mesh& mesh, std::span<const char> keep, const TriangleSoup& input,
                       TetLabels mode, WindingRule rule) {
  PartLabels result;
  mode = resolve(mode, input);
  result.labels.assign(mesh.tet_slots(), 0);
  for (Index t = 0; t < mesh.tet_slots(); ++t)
    if (keep[t]) result.labels[t] = 1;
  if (mode == TetLabels::none) return result;

  InputParts parts;
  if (mode == TetLabels::parts) parts = parts_by_region(input);
  if (mode == TetLabels::components) parts = parts_by_component(input);
  if (parts.labels.size() > kMaxLabelledParts) {
    throw RunError("the input has " + std::to_string(parts.labels.size()) +
                   " parts; tets can be labelled by at most " + std::to_string(kMaxLabelledParts));
  }
  const std::vector<std::int32_t> regions = region_labels(mesh);
  const std::vector<Index> largest = largest_kept_tets(mesh, keep, regions);
  std::vector<Vec3d> points;
  std::vector<std::int32_t> point_of_region(largest.size(), -1);
  for (std::size_t r = 0; r < largest.size(); ++r) {
    if (largest[r] == kNoTet) continue;
    point_of_region[r] = std::int32_t(points.size());
    points.push_back(tet_centroid(mesh, largest[r]));
  }
  const std::vector<std::int32_t> point_labels = mode == TetLabels::winding
                                                     ? label_points_by_winding(input, points, rule)
                                                     : label_points(input, parts, points, rule);
  for (Index t = 0; t < mesh.tet_slots(); ++t)
    if (keep[t]) result.labels[t] = point_labels[point_of_region[regions[t]]];
  result.names = std::move(parts.names);
  return result;
}

}  // namespace mr::tetmesh::detail

namespace mr::tetmesh {

TetLabels tet_labels_named(std::string_view name) {
  if (name == "auto") return TetLabels::automatic;
  if (name == "none") return TetLabels::none;
  if (name == "regions") return TetLabels::parts;
  if (name == "components") return TetLabels::components;
  if (name == "winding") return TetLabels::winding;
  throw UsageError("labels must be auto, regions, components, winding or none, got '" + std::string(name) +
                   "'");
}

}  // namespace mr::tetmesh
