// Decoding a Draco mesh into a soup. Nothing Draco hands back is trusted:
// face indices, point-to-value mappings and attribute buffers are checked
// before use, so a malformed file ends in InputError, never in a bad read.
//
// A soup vertex is a distinct combination of the position, normal, uv and
// colour values of a Draco point: points that differ only in other
// attributes (the face-region attribute of a .drc) become one vertex again.

#include "draco_codec_detail.h"
#include "draco_declared_sizes.h"
#include "draco_trial_decode.h"

#include <mr/core/errors.h>

#include <draco/compression/decode.h>
#include <draco/core/draco_types.h>
#include <draco/mesh/mesh.h>

#include <cmath>
#include <exception>
#include <memory>
#include <unordered_map>

namespace mr::plugins {
namespace detail {
namespace {

using Type = draco::GeometryAttribute;

std::unique_ptr<draco::Mesh> decode_mesh(std::string_view bytes, const std::string& source) {
  const auto invalid = [&](const std::string& why) {
    return InputError(source, "not a valid Draco mesh: " + why);
  };
  check_draco_declared_sizes(bytes, source);
  trial_decode_draco(bytes, source);
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  try {
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) throw invalid(result.status().error_msg_string());
    std::unique_ptr<draco::Mesh> mesh = std::move(result).value();
    if (!mesh) throw invalid("the decoder returned no mesh");
    return mesh;
  } catch (const std::bad_alloc&) {
    throw invalid("its sizes exceed the memory available");
  } catch (const std::length_error&) {
    throw invalid("its sizes are out of range");
  }
}

/// One validated attribute: every point maps to a stored value.
struct CheckedAttribute {
  const draco::PointAttribute* attribute = nullptr;
  const char* what = "";
  explicit operator bool() const { return attribute != nullptr; }
};

const draco::PointAttribute* find_attribute(const draco::Mesh& mesh, int unique_id, Type::Type type,
                                            const std::string& source, const char* what) {
  if (unique_id < 0) return mesh.GetNamedAttribute(type);
  const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(static_cast<std::uint32_t>(unique_id));
  if (!attribute)
    throw InputError(source, std::string("the Draco mesh has no ") + what + " attribute with unique id " +
                                 std::to_string(unique_id));
  return attribute;
}

CheckedAttribute check_attribute(const draco::Mesh& mesh, const draco::PointAttribute* attribute,
                                 int components, const std::string& source, const char* what) {
  if (!attribute) return {};
  const auto bad = [&](const std::string& why) {
    return InputError(source, std::string("Draco ") + what + " attribute " + why);
  };
  if (attribute->num_components() < components)
    throw bad("has " + std::to_string(attribute->num_components()) + " components, needs " +
              std::to_string(components));
  // Draco would convert stored bytes to values by loading them as bool:
  // undefined for any byte but 0 and 1 (fuzzer find). No mesh stores its
  // positions, normals, uvs or colours as booleans.
  if (attribute->data_type() == draco::DT_BOOL) throw bad("holds booleans, not numbers");
  const std::int64_t item = draco::DataTypeLength(attribute->data_type());
  const draco::DataBuffer* data = attribute->buffer();
  if (item <= 0 || !data || attribute->byte_stride() < item * attribute->num_components() ||
      attribute->byte_offset() < 0)
    throw bad("has an invalid layout");
  if (attribute->size() > 0) {  // the last value must end inside the buffer
    const std::uint64_t size = data->data_size();
    const auto offset = static_cast<std::uint64_t>(attribute->byte_offset());
    const auto stride = static_cast<std::uint64_t>(attribute->byte_stride());
    const auto value_bytes = static_cast<std::uint64_t>(item) * attribute->num_components();
    if (offset + value_bytes > size || (attribute->size() - 1) > (size - offset - value_bytes) / stride)
      throw bad("is larger than its data");
  }
  const std::uint32_t points = mesh.num_points();
  if (!attribute->is_mapping_identity() && attribute->indices_map_size() < points)
    throw bad("does not map every point");
  for (draco::PointIndex p(0); p < points; ++p)
    if (attribute->mapped_index(p).value() >= attribute->size()) throw bad("maps a point to a missing value");
  return {attribute, what};
}

void check_faces(const draco::Mesh& mesh, const std::string& source) {
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.face(f)[c].value() >= mesh.num_points())
        throw InputError(source, "Draco face " + std::to_string(f.value()) + " refers to a missing point");
}

template <int N>
std::array<float, N> value_of(const CheckedAttribute& checked, draco::PointIndex point,
                              const std::string& source) {
  std::array<float, N> value{};
  if (!checked.attribute->ConvertValue<float>(checked.attribute->mapped_index(point), N, value.data()))
    throw InputError(source, std::string("cannot convert a Draco ") + checked.what + " value");
  for (float x : value)
    if (!std::isfinite(x))
      throw InputError(source, std::string("Draco ") + checked.what + " value is not finite");
  return value;
}

struct SoupAttributes {
  CheckedAttribute position, normal, uv, color, region;
};

struct KeyHash {
  std::size_t operator()(const std::array<std::uint32_t, 4>& key) const {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (std::uint32_t k : key) h = (h ^ k) * 0x100000001B3ull;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

/// The soup vertex of each point; returns the vertex count through `num_vertices`.
std::vector<Index> vertex_of_points(const draco::Mesh& mesh, const SoupAttributes& a,
                                    std::size_t& num_vertices) {
  const std::uint32_t points = mesh.num_points();
  std::vector<Index> vertex(points);
  if (a.position.attribute->is_mapping_identity()) {  // distinct positions: one vertex a point
    for (std::uint32_t p = 0; p < points; ++p) vertex[p] = p;
    num_vertices = points;
    return vertex;
  }
  const auto value_index = [](const CheckedAttribute& c, draco::PointIndex p) {
    return c ? c.attribute->mapped_index(p).value() : 0u;
  };
  std::unordered_map<std::array<std::uint32_t, 4>, Index, KeyHash> seen;
  seen.reserve(points);
  for (draco::PointIndex p(0); p < points; ++p) {
    const std::array<std::uint32_t, 4> key{value_index(a.position, p), value_index(a.normal, p),
                                           value_index(a.uv, p), value_index(a.color, p)};
    vertex[p.value()] = seen.try_emplace(key, static_cast<Index>(seen.size())).first->second;
  }
  num_vertices = seen.size();
  return vertex;
}

void fill_vertices(const draco::Mesh& mesh, const SoupAttributes& a,
                   const std::vector<Index>& vertex_of_point, TriangleSoup& soup, const std::string& source) {
  const std::size_t n = soup.positions.size();
  if (a.normal) soup.normals.resize(n);
  if (a.uv) soup.uvs.resize(n);
  if (a.color) soup.colors.resize(n);
  std::vector<bool> done(n, false);
  for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
    const Index v = vertex_of_point[p.value()];
    if (done[v]) continue;
    done[v] = true;
    const auto xyz = value_of<3>(a.position, p, source);
    soup.positions[v] = Vec3d(xyz[0], xyz[1], xyz[2]);
    if (a.normal) soup.normals[v] = Eigen::Map<const Vec3f>(value_of<3>(a.normal, p, source).data());
    if (a.uv) soup.uvs[v] = Eigen::Map<const Vec2f>(value_of<2>(a.uv, p, source).data());
    if (a.color) {
      auto rgba = value_of<4>(a.color, p, source);
      if (a.color.attribute->num_components() < 4) rgba[3] = 1.0f;
      soup.colors[v] = Eigen::Map<const Vec4f>(rgba.data());
    }
  }
}

void fill_faces(const draco::Mesh& mesh, const SoupAttributes& a, const std::vector<Index>& vertex_of_point,
                TriangleSoup& soup, const std::string& source) {
  soup.triangles.resize(mesh.num_faces());
  if (a.region) soup.face_regions.resize(mesh.num_faces());
  for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh.face(f);
    for (int c = 0; c < 3; ++c) soup.triangles[f.value()][c] = vertex_of_point[face[c].value()];
    if (!a.region) continue;
    std::int32_t region = 0;
    if (!a.region.attribute->ConvertValue<std::int32_t>(a.region.attribute->mapped_index(face[0]), 1,
                                                        &region))
      throw InputError(source, "cannot convert a Draco face region value");
    soup.face_regions[f.value()] = region;
  }
}

SoupAttributes find_soup_attributes(const draco::Mesh& mesh, const DracoAttributeIds& ids, bool with_regions,
                                    const std::string& source) {
  SoupAttributes a;
  const auto find = [&](int id, Type::Type type, int components, const char* what) {
    return check_attribute(mesh, find_attribute(mesh, id, type, source, what), components, source, what);
  };
  a.position = find(ids.position, Type::POSITION, 3, "position");
  if (!a.position) throw InputError(source, "the Draco mesh has no position attribute");
  a.normal = find(ids.normal, Type::NORMAL, 3, "normal");
  a.uv = find(ids.uv, Type::TEX_COORD, 2, "texture coordinate");
  a.color = find(ids.color, Type::COLOR, 3, "colour");
  if (with_regions) {
    const int region_id = mesh.GetAttributeIdByMetadataEntry(kRegionMetadataKey, kRegionMetadataValue);
    if (region_id >= 0) a.region = check_attribute(mesh, mesh.attribute(region_id), 1, source, "face region");
  }
  return a;
}

}  // namespace

TriangleSoup decode_draco_mesh(std::string_view bytes, const std::string& source,
                               const DracoAttributeIds& ids, bool with_regions) {
  const std::unique_ptr<draco::Mesh> mesh = decode_mesh(bytes, source);
  check_faces(*mesh, source);
  const SoupAttributes attributes = find_soup_attributes(*mesh, ids, with_regions, source);
  std::size_t num_vertices = 0;
  const std::vector<Index> vertex_of_point = vertex_of_points(*mesh, attributes, num_vertices);
  TriangleSoup soup;
  soup.positions.resize(num_vertices);
  fill_vertices(*mesh, attributes, vertex_of_point, soup, source);
  fill_faces(*mesh, attributes, vertex_of_point, soup, source);
  return soup;
}

}  // namespace detail

TriangleSoup decode_draco(std::string_view bytes, const std::string& source, const DracoAttributeIds& ids) {
  return detail::decode_draco_mesh(bytes, source, ids, false);
}

}  // namespace mr::plugins
