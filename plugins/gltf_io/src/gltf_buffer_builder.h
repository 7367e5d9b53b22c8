#pragma once
// The binary buffer of a glTF file being written, with its bufferViews and
// accessors as JSON. Every view starts on a 4-byte boundary.

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace mr::plugins::gltf {

inline constexpr int array_buffer = 34962;
inline constexpr int element_array_buffer = 34963;
inline constexpr int component_unsigned_short = 5123;
inline constexpr int component_unsigned_int = 5125;
inline constexpr int component_float = 5126;

class BufferBuilder {
 public:
  /// Appends `size` bytes as a new bufferView; returns its index.
  int add_view(const void* data, std::size_t size, std::optional<int> target);

  /// Appends an accessor; returns its index.
  int add_accessor(nlohmann::json accessor);

  const std::vector<char>& bytes() const { return bytes_; }
  const nlohmann::json& views() const { return views_; }
  const nlohmann::json& accessors() const { return accessors_; }

 private:
  std::vector<char> bytes_;
  nlohmann::json views_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
};

}  // namespace mr::plugins::gltf
