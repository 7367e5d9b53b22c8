// Encoding a soup as a Draco mesh.
//
// Draco points are the soup's vertices, except where face regions are carried:
// a region is a per-point GENERIC attribute, so a vertex shared by faces of
// different regions needs one point per region. Those extra points share the
// vertex's attribute *values* (explicit point-to-value mapping), so the
// edgebreaker still sees one vertex and the decoder can merge them back.

#include "draco_codec_detail.h"

#include <mr/core/errors.h>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/encode.h>
#include <draco/compression/expert_encode.h>
#include <draco/mesh/mesh.h>
#include <draco/metadata/geometry_metadata.h>

#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>

namespace mr::plugins {
namespace detail {
namespace {

/// Which point of the Draco mesh each face corner uses, and which soup vertex each point stands for.
struct PointLayout {
  std::vector<Index> point_vertex;
  std::vector<std::int32_t> point_region;  ///< empty unless regions are encoded
  std::vector<std::array<Index, 3>> face_points;
};

PointLayout one_point_per_vertex(const TriangleSoup& soup) {
  PointLayout layout;
  layout.point_vertex.resize(soup.num_vertices());
  for (Index v = 0; v < soup.num_vertices(); ++v) layout.point_vertex[v] = v;
  layout.face_points = soup.triangles;
  return layout;
}

// Point v is vertex v with the region of the first face that uses it; each
// further (vertex, region) pair gets a new point after the vertices.
PointLayout one_point_per_vertex_and_region(const TriangleSoup& soup) {
  PointLayout layout = one_point_per_vertex(soup);
  constexpr std::int32_t unset = std::numeric_limits<std::int32_t>::min();
  layout.point_region.assign(soup.num_vertices(), unset);
  std::unordered_map<std::uint64_t, Index> extra_points;
  for (std::size_t f = 0; f < soup.num_triangles(); ++f) {
    const std::int32_t region = soup.face_regions[f];
    for (Index& point : layout.face_points[f]) {
      const Index vertex = point;
      if (layout.point_region[vertex] == unset) layout.point_region[vertex] = region;
      if (layout.point_region[vertex] == region) continue;
      const std::uint64_t key = (std::uint64_t{vertex} << 32) | static_cast<std::uint32_t>(region);
      auto [it, added] = extra_points.try_emplace(key, static_cast<Index>(layout.point_vertex.size()));
      if (added) {
        layout.point_vertex.push_back(vertex);
        layout.point_region.push_back(region);
      }
      point = it->second;
    }
  }
  for (std::int32_t& region : layout.point_region)
    if (region == unset) region = 0;  // isolated vertex
  return layout;
}

void check_float_range(const TriangleSoup& soup) {
  constexpr double limit = std::numeric_limits<float>::max();
  for (const Vec3d& p : soup.positions)
    if (!(p.cwiseAbs().maxCoeff() <= limit))
      throw RunError("Draco stores positions as 32-bit floats; a coordinate is out of float range");
}

/// Adds one attribute whose values are indexed by soup vertex; returns its attribute id.
template <class Value>
int add_vertex_attribute(draco::Mesh& mesh, const PointLayout& layout, draco::GeometryAttribute::Type type,
                         const std::vector<Value>& values, int components) {
  draco::GeometryAttribute descriptor;
  const auto stride = static_cast<std::int64_t>(sizeof(float) * components);
  descriptor.Init(type, nullptr, static_cast<std::uint8_t>(components), draco::DT_FLOAT32, false, stride, 0);
  const bool identity = layout.point_vertex.size() == values.size();
  const int id = mesh.AddAttribute(descriptor, identity, static_cast<std::uint32_t>(values.size()));
  draco::PointAttribute* attribute = mesh.attribute(id);
  for (std::size_t v = 0; v < values.size(); ++v) {
    std::array<float, 4> value{};
    for (int c = 0; c < components; ++c) value[c] = static_cast<float>(values[v][c]);
    attribute->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(v)), value.data());
  }
  if (!identity) {
    attribute->SetExplicitMapping(layout.point_vertex.size());
    for (std::size_t p = 0; p < layout.point_vertex.size(); ++p)
      attribute->SetPointMapEntry(draco::PointIndex(static_cast<std::uint32_t>(p)),
                                  draco::AttributeValueIndex(layout.point_vertex[p]));
  }
  return id;
}

int add_region_attribute(draco::Mesh& mesh, const std::vector<std::int32_t>& point_region) {
  draco::GeometryAttribute descriptor;
  descriptor.Init(draco::GeometryAttribute::GENERIC, nullptr, 1, draco::DT_INT32, false, sizeof(std::int32_t),
                  0);
  const int id = mesh.AddAttribute(descriptor, true, static_cast<std::uint32_t>(point_region.size()));
  draco::PointAttribute* attribute = mesh.attribute(id);
  for (std::size_t p = 0; p < point_region.size(); ++p)
    attribute->SetAttributeValue(draco::AttributeValueIndex(static_cast<std::uint32_t>(p)), &point_region[p]);
  auto metadata = std::make_unique<draco::AttributeMetadata>();
  metadata->AddEntryString(kRegionMetadataKey, kRegionMetadataValue);
  mesh.AddAttributeMetadata(id, std::move(metadata));
  return id;
}

struct BuiltMesh {
  draco::Mesh mesh;
  int position = -1, normal = -1, uv = -1, color = -1;  ///< attribute ids (not unique ids)
};

void build_mesh(const TriangleSoup& soup, const PointLayout& layout, BuiltMesh& built) {
  draco::Mesh& mesh = built.mesh;
  mesh.set_num_points(static_cast<std::uint32_t>(layout.point_vertex.size()));
  using Type = draco::GeometryAttribute;
  built.position = add_vertex_attribute(mesh, layout, Type::POSITION, soup.positions, 3);
  if (soup.has_normals()) built.normal = add_vertex_attribute(mesh, layout, Type::NORMAL, soup.normals, 3);
  if (soup.has_uvs()) built.uv = add_vertex_attribute(mesh, layout, Type::TEX_COORD, soup.uvs, 2);
  if (soup.has_colors()) built.color = add_vertex_attribute(mesh, layout, Type::COLOR, soup.colors, 4);
  if (!layout.point_region.empty()) add_region_attribute(mesh, layout.point_region);
  mesh.SetNumFaces(layout.face_points.size());
  for (std::size_t f = 0; f < layout.face_points.size(); ++f) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(layout.face_points[f][c]);
    mesh.SetFace(draco::FaceIndex(static_cast<std::uint32_t>(f)), face);
  }
}

bool has_repeated_index(const TriangleSoup& soup) {
  for (const Triangle& t : soup.triangles)
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  return false;
}

struct EncodeResult {
  draco::EncoderBuffer buffer;
  std::size_t encoded_faces = 0;
  std::size_t encoded_points = 0;
};

EncodeResult run_encoder(const BuiltMesh& built, const io::DracoOptions& options, bool sequential) {
  draco::ExpertEncoder encoder(built.mesh);
  encoder.SetTrackEncodedProperties(true);
  encoder.SetSpeedOptions(options.speed, options.speed);
  if (const auto& grid = options.position_grid)
    encoder.SetAttributeExplicitQuantization(built.position, grid->bits, 3, grid->origin.data(), grid->range);
  else
    encoder.SetAttributeQuantization(built.position, options.position_bits);
  if (built.normal >= 0) encoder.SetAttributeQuantization(built.normal, options.normal_bits);
  if (built.uv >= 0) encoder.SetAttributeQuantization(built.uv, options.uv_bits);
  if (built.color >= 0) encoder.SetAttributeQuantization(built.color, options.color_bits);
  if (sequential) encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
  EncodeResult result;
  const draco::Status status = encoder.EncodeToBuffer(&result.buffer);
  if (!status.ok()) throw RunError("Draco could not encode the mesh: " + status.error_msg_string());
  result.encoded_faces = encoder.num_encoded_faces();
  result.encoded_points = encoder.num_encoded_points();
  return result;
}

void check_options(const io::DracoOptions& options) {
  const auto check_bits = [](int bits, const char* what) {
    if (bits < 1 || bits > 30)
      throw RunError(std::string("Draco ") + what + " quantization must be 1 to 30 bits, not " +
                     std::to_string(bits));
  };
  check_bits(options.position_bits, "position");
  check_bits(options.normal_bits, "normal");
  check_bits(options.uv_bits, "texture coordinate");
  check_bits(options.color_bits, "colour");
  if (options.speed < 0 || options.speed > 10)
    throw RunError("Draco speed must be 0 to 10, not " + std::to_string(options.speed));
}

}  // namespace

DracoEncoded encode_draco_mesh(const TriangleSoup& soup, const io::DracoOptions& options, bool with_regions) {
  check_options(options);
  if (std::string problem = find_soup_inconsistency(soup); !problem.empty())
    throw RunError("cannot Draco-encode an inconsistent mesh: " + problem);
  check_float_range(soup);
  const bool regions = with_regions && soup.has_face_regions();
  BuiltMesh built;
  build_mesh(soup, regions ? one_point_per_vertex_and_region(soup) : one_point_per_vertex(soup), built);

  // The edgebreaker drops faces with a repeated vertex index (and would drop
  // anything else it cannot traverse): sequential encoding keeps every face.
  const bool sequential = soup.num_triangles() == 0 || has_repeated_index(soup);
  EncodeResult result = run_encoder(built, options, sequential);
  if (result.encoded_faces != soup.num_triangles() && !sequential) result = run_encoder(built, options, true);
  if (result.encoded_faces != soup.num_triangles())
    throw RunError("Draco encoded " + std::to_string(result.encoded_faces) + " of " +
                   std::to_string(soup.num_triangles()) + " triangles");

  DracoEncoded encoded;
  encoded.bytes.assign(result.buffer.data(), result.buffer.data() + result.buffer.size());
  encoded.num_points = result.encoded_points;
  encoded.num_faces = result.encoded_faces;
  const auto unique_id = [&](int attribute_id) {
    return attribute_id < 0 ? -1 : static_cast<int>(built.mesh.attribute(attribute_id)->unique_id());
  };
  encoded.ids = {unique_id(built.position), unique_id(built.normal), unique_id(built.uv),
                 unique_id(built.color)};
  return encoded;
}

}  // namespace detail

DracoEncoded encode_draco(const TriangleSoup& soup, const io::DracoOptions& options) {
  return detail::encode_draco_mesh(soup, options, false);
}

}  // namespace mr::plugins
