#pragma once
// Basic value types shared by every part of the library.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>

namespace mr {

using Vec3d = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Vec2f = Eigen::Vector2f;
using Vec4f = Eigen::Vector4f;

/// Vertex index. 32 bits: inputs beyond 4 billion vertices are out of scope.
using Index = std::uint32_t;

using Triangle = std::array<Index, 3>;
using Tet = std::array<Index, 4>;

}  // namespace mr
