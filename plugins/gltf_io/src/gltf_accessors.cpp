#include "gltf_accessors.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mr::plugins::gltf {
namespace {

std::size_t component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

int element_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
      return 4;
    default:
      return 0;
  }
}

template <class T>
T load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

float component_as_float(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? load<std::uint8_t>(p) / 255.0f : load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return normalized ? load<std::uint16_t>(p) / 65535.0f : load<std::uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return normalized ? std::max(load<std::int8_t>(p) / 127.0f, -1.0f) : load<std::int8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return normalized ? std::max(load<std::int16_t>(p) / 32767.0f, -1.0f) : load<std::int16_t>(p);
    default:
      return static_cast<float>(load<std::uint32_t>(p));
  }
}

std::uint32_t component_as_index(const unsigned char* p, int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return load<std::uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return load<std::uint16_t>(p);
    default:
      return load<std::uint32_t>(p);
  }
}

}  // namespace

void AccessorReader::fail(const std::string& problem) const { throw InputError(path_, problem); }

AccessorReader::View AccessorReader::view(int index, const char* what) const {
  const std::string name = std::string(what) + " accessor " + std::to_string(index);
  if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
    fail(std::string(what) + " refers to accessor " + std::to_string(index) + ", which does not exist");
  const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
  if (accessor.sparse.isSparse) fail(name + " is sparse; sparse accessors are not supported");
  if (accessor.bufferView < 0 || static_cast<std::size_t>(accessor.bufferView) >= model_.bufferViews.size())
    fail(name + " has no valid bufferView (accessors without data are not supported)");
  const tinygltf::BufferView& buffer_view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
  if (buffer_view.buffer < 0 || static_cast<std::size_t>(buffer_view.buffer) >= model_.buffers.size())
    fail("bufferView " + std::to_string(accessor.bufferView) + " refers to a buffer that does not exist");
  const std::vector<unsigned char>& buffer =
      model_.buffers[static_cast<std::size_t>(buffer_view.buffer)].data;
  if (buffer_view.byteOffset > buffer.size() ||
      buffer_view.byteLength > buffer.size() - buffer_view.byteOffset)
    fail("bufferView " + std::to_string(accessor.bufferView) + " (offset " +
         std::to_string(buffer_view.byteOffset) + ", length " + std::to_string(buffer_view.byteLength) +
         ") lies outside its buffer of " + std::to_string(buffer.size()) + " bytes");

  View v;
  v.component_type = accessor.componentType;
  v.components = element_components(accessor.type);
  v.normalized = accessor.normalized;
  const std::size_t size = component_size(accessor.componentType);
  if (size == 0) fail(name + " has an invalid componentType " + std::to_string(accessor.componentType));
  if (v.components == 0) fail(name + " has an unsupported type (matrices are not mesh data)");
  const std::size_t element = size * static_cast<std::size_t>(v.components);
  v.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element;
  if (v.stride < element)
    fail(name + ": byteStride " + std::to_string(v.stride) + " is smaller than an element");
  v.count = accessor.count;
  if (v.count > 0) {
    const std::size_t available = buffer_view.byteLength;
    // (count-1)*stride + offset + element <= available, written so nothing overflows.
    if (accessor.byteOffset > available || element > available - accessor.byteOffset ||
        v.count - 1 > (available - accessor.byteOffset - element) / v.stride)
      fail(name + " (offset " + std::to_string(accessor.byteOffset) + ", " + std::to_string(v.count) +
           " elements, stride " + std::to_string(v.stride) + ") runs past the end of its bufferView of " +
           std::to_string(available) + " bytes");
  }
  v.data = buffer.data() + buffer_view.byteOffset + accessor.byteOffset;
  return v;
}

std::size_t AccessorReader::count(int index, const char* what) const { return view(index, what).count; }

std::vector<float> AccessorReader::read_floats(int index, std::initializer_list<int> allowed_components,
                                               int& components, const char* what) const {
  const View v = view(index, what);
  if (std::find(allowed_components.begin(), allowed_components.end(), v.components) ==
      allowed_components.end())
    fail(std::string(what) + " accessor " + std::to_string(index) + " has " + std::to_string(v.components) +
         " components per element, which is not allowed for it");
  components = v.components;
  const std::size_t size = component_size(v.component_type);
  std::vector<float> values(v.count * static_cast<std::size_t>(v.components));
  float* out = values.data();
  for (std::size_t i = 0; i < v.count; ++i) {
    const unsigned char* element = v.data + i * v.stride;
    for (int c = 0; c < v.components; ++c)
      *out++ =
          component_as_float(element + static_cast<std::size_t>(c) * size, v.component_type, v.normalized);
  }
  return values;
}

std::vector<Index> AccessorReader::read_indices(int index, std::size_t vertex_count) const {
  const View v = view(index, "indices");
  if (v.components != 1) fail("indices accessor " + std::to_string(index) + " is not SCALAR");
  if (v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      v.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail("indices accessor " + std::to_string(index) + " is not of an unsigned integer type");
  std::vector<Index> indices(v.count);
  for (std::size_t i = 0; i < v.count; ++i) {
    const std::uint32_t value = component_as_index(v.data + i * v.stride, v.component_type);
    if (value >= vertex_count)
      fail("index " + std::to_string(value) + " in accessor " + std::to_string(index) + " is out of range (" +
           std::to_string(vertex_count) + " vertices)");
    indices[i] = value;
  }
  return indices;
}

}  // namespace mr::plugins::gltf
