#pragma once
// Bounds-checked reading of glTF accessors. Every index, offset, stride and
// count is checked against the bytes really present before anything is read
// or allocated, so a hostile file cannot make us read out of bounds or
// allocate memory sized from a count it claims.

#include <mr/core/types.h>

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace mr::plugins::gltf {

class AccessorReader {
 public:
  AccessorReader(const tinygltf::Model& model, std::string path) : model_(model), path_(std::move(path)) {}

  /// Number of elements of accessor `index`, after checking that they all lie in their buffer.
  std::size_t count(int index, const char* what) const;

  /// The accessor's elements as floats, `components` per element (normalized
  /// integer types scaled to [0,1] or [-1,1]). `allowed_components` lists the
  /// element sizes the caller accepts, e.g. {3, 4} for colours; the result has
  /// the accessor's own element size, returned in `components`.
  std::vector<float> read_floats(int index, std::initializer_list<int> allowed_components, int& components,
                                 const char* what) const;

  /// Index data; every value is checked to be < vertex_count.
  std::vector<Index> read_indices(int index, std::size_t vertex_count) const;

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  struct View {
    const unsigned char* data = nullptr;
    std::size_t count = 0;
    std::size_t stride = 0;
    int components = 0;
    int component_type = 0;
    bool normalized = false;
  };
  View view(int index, const char* what) const;

  const tinygltf::Model& model_;
  std::string path_;
};

}  // namespace mr::plugins::gltf
