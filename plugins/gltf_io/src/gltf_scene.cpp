#include "gltf_scene.h"

#include <mr/core/errors.h>

#include <Eigen/Geometry>

#include <cmath>

namespace mr::plugins::gltf {
namespace {

void check_finite(const std::vector<double>& values, int node, const char* what, const std::string& path) {
  for (double v : values)
    if (!std::isfinite(v))
      throw InputError(path, "node " + std::to_string(node) + " has a non-finite " + what);
}

void check_size(const std::vector<double>& values, std::size_t expected, int node, const char* what,
                const std::string& path) {
  if (!values.empty() && values.size() != expected)
    throw InputError(path, "node " + std::to_string(node) + ": " + what + " has " +
                               std::to_string(values.size()) + " numbers instead of " +
                               std::to_string(expected));
  check_finite(values, node, what, path);
}

Eigen::Matrix4d local_transform(const tinygltf::Node& node, int index, const std::string& path) {
  check_size(node.matrix, 16, index, "matrix", path);
  check_size(node.translation, 3, index, "translation", path);
  check_size(node.rotation, 4, index, "rotation", path);
  check_size(node.scale, 3, index, "scale", path);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (!node.matrix.empty()) {
    for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[static_cast<std::size_t>(i)];  // column-major
    return m;
  }
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (!node.translation.empty())
    t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (!node.rotation.empty()) {
    Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1],
                         node.rotation[2]);  // glTF stores x,y,z,w
    if (q.norm() == 0)
      throw InputError(path, "node " + std::to_string(index) + " has a zero rotation quaternion");
    t.rotate(q.normalized());
  }
  if (!node.scale.empty()) t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return t.matrix();
}

class SceneWalker {
 public:
  SceneWalker(const tinygltf::Model& model, const std::string& path)
      : model_(model), path_(path), visited_(model.nodes.size(), false) {}

  // Depth-first with an explicit stack: a hostile hierarchy cannot overflow
  // the call stack, and a node reached twice (a cycle or a shared child)
  // is an error, since glTF requires disjoint trees.
  void add_root(int root) {
    check_node(root, "a scene");
    if (visited_[static_cast<std::size_t>(root)]) return;  // a root shared by several scenes
    std::vector<std::pair<int, Eigen::Matrix4d>> stack{{root, Eigen::Matrix4d::Identity()}};
    visited_[static_cast<std::size_t>(root)] = true;
    while (!stack.empty()) {
      auto [index, parent] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
      const Eigen::Matrix4d world = parent * local_transform(node, index, path_);
      if (node.mesh >= 0) {
        if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size())
          throw InputError(path_, "node " + std::to_string(index) + " refers to mesh " +
                                      std::to_string(node.mesh) + ", which does not exist");
        instances_.push_back({node.mesh, world});
      }
      for (int child : node.children) {
        check_node(child, ("node " + std::to_string(index)).c_str());
        if (visited_[static_cast<std::size_t>(child)])
          throw InputError(path_, "the node hierarchy is not a tree: node " + std::to_string(child) +
                                      " is reached more than once");
        visited_[static_cast<std::size_t>(child)] = true;
        stack.emplace_back(child, world);
      }
    }
  }

  std::vector<MeshInstance> take() { return std::move(instances_); }

 private:
  void check_node(int index, const char* from) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      throw InputError(
          path_, std::string(from) + " refers to node " + std::to_string(index) + ", which does not exist");
  }

  const tinygltf::Model& model_;
  const std::string& path_;
  std::vector<bool> visited_;
  std::vector<MeshInstance> instances_;
};

}  // namespace

std::vector<MeshInstance> mesh_instances(const tinygltf::Model& model, const std::string& path) {
  if (model.scenes.empty()) {
    std::vector<MeshInstance> all(model.meshes.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i].mesh = static_cast<int>(i);
    return all;
  }
  if (model.defaultScene >= static_cast<int>(model.scenes.size()))
    throw InputError(path, "the default scene " + std::to_string(model.defaultScene) + " does not exist");
  SceneWalker walker(model, path);
  if (model.defaultScene >= 0) {
    for (int root : model.scenes[static_cast<std::size_t>(model.defaultScene)].nodes) walker.add_root(root);
  } else {
    for (const tinygltf::Scene& scene : model.scenes)
      for (int root : scene.nodes) walker.add_root(root);
  }
  return walker.take();
}

}  // namespace mr::plugins::gltf
