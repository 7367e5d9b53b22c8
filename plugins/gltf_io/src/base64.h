#pragma once

#include <string>
#include <string_view>

namespace mr::plugins::gltf {

/// Standard base64 (RFC 4648) with '=' padding, as glTF data URIs use.
std::string base64_encode(std::string_view bytes);

}  // namespace mr::plugins::gltf
