#include "gltf_buffer_builder.h"

#include <cstring>

namespace mr::plugins::gltf {

int BufferBuilder::add_view(const void* data, std::size_t size, std::optional<int> target) {
  bytes_.resize((bytes_.size() + 3) / 4 * 4, '\0');
  const std::size_t offset = bytes_.size();
  bytes_.resize(offset + size);
  if (size > 0) std::memcpy(bytes_.data() + offset, data, size);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
  if (target) view["target"] = *target;
  views_.push_back(std::move(view));
  return static_cast<int>(views_.size()) - 1;
}

int BufferBuilder::add_accessor(nlohmann::json accessor) {
  accessors_.push_back(std::move(accessor));
  return static_cast<int>(accessors_.size()) - 1;
}

}  // namespace mr::plugins::gltf
