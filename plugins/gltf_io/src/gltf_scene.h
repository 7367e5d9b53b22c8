#pragma once
// Which meshes a glTF file shows, and where: the nodes of the default scene
// (or of every scene if none is the default; every mesh untransformed if the
// file has no scenes), with each node's world transform.

#include <tiny_gltf.h>
#include <Eigen/Core>

#include <string>
#include <vector>

namespace mr::plugins::gltf {

struct MeshInstance {
  int mesh = -1;
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();
};

/// Throws InputError naming `path` on an index out of range, a malformed or
/// non-finite transform, or a node hierarchy that is not a set of trees.
std::vector<MeshInstance> mesh_instances(const tinygltf::Model& model, const std::string& path);

}  // namespace mr::plugins::gltf
