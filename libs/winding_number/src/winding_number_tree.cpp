#include <mr/winding_number/winding_number.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace mr {
namespace {

using Node = WindingNumberTree::Node;
using Corners = WindingNumberTree::Corners;

constexpr double inv_four_pi = 0.25 / std::numbers::pi;
// Subtrees smaller than this are built on the calling thread.
constexpr std::size_t parallel_build_threshold = 4096;

// Index of the symmetric pair (i, k) among xx, xy, xz, yy, yz, zz.
constexpr int sym(int i, int k) {
  constexpr int table[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
  return table[i][k];
}

// Moments of a single triangle about `center`, added to `node`. The order-1
// and order-2 integrals over a triangle are exact: int y dA = A * centroid and
// int y y^T dA = A/12 (sum_a d_a d_a^T + s s^T) with d_a the corners and s their sum.
void add_triangle_moments(const Corners& t, const Vec3d& center, Node& node) {
  const Vec3d area_normal = 0.5 * (t.b - t.a).cross(t.c - t.a);
  const Vec3d d[3] = {t.a - center, t.b - center, t.c - center};
  const Vec3d s = d[0] + d[1] + d[2];
  node.normal_sum += area_normal;
  node.first += (s / 3.0) * area_normal.transpose();
  for (int i = 0; i < 3; ++i)
    for (int k = i; k < 3; ++k) {
      const double yy = (d[0][i] * d[0][k] + d[1][i] * d[1][k] + d[2][i] * d[2][k] + s[i] * s[k]) / 12.0;
      for (int j = 0; j < 3; ++j) node.second[sym(i, k) * 3 + j] += yy * area_normal[j];
    }
}

// Moments of a child about its own centre, translated to the parent's centre.
void add_child_moments(const Node& child, const Vec3d& center, Node& node) {
  const Vec3d delta = child.center - center;
  node.normal_sum += child.normal_sum;
  node.first += child.first + delta * child.normal_sum.transpose();
  for (int i = 0; i < 3; ++i)
    for (int k = i; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        node.second[sym(i, k) * 3 + j] += child.second[sym(i, k) * 3 + j] + delta[i] * child.first(k, j) +
                                          delta[k] * child.first(i, j) +
                                          delta[i] * delta[k] * child.normal_sum[j];
}

class TreeBuilder {
 public:
  TreeBuilder(const std::vector<Corners>& triangles, std::size_t leaf_size)
      : triangles_(triangles), leaf_size_(leaf_size), order_(triangles.size()), centroids_(triangles.size()) {
    std::iota(order_.begin(), order_.end(), 0u);
    for (std::size_t i = 0; i < triangles.size(); ++i)
      centroids_[i] = (triangles[i].a + triangles[i].b + triangles[i].c) / 3.0;
  }

  // Fills `nodes` in pre-order and returns the triangle permutation. Node
  // indices depend only on subtree sizes, so parallel subtrees write to
  // ranges known in advance and the result is the same on any thread count.
  std::vector<std::uint32_t> build(std::vector<Node>& nodes) {
    if (triangles_.empty()) return {};
    nodes.resize(count_nodes(triangles_.size()));
    build_subtree(nodes, 0, 0, triangles_.size());
    return std::move(order_);
  }

 private:
  std::size_t count_nodes(std::size_t n) {
    if (n <= leaf_size_) return 1;
    if (auto it = node_counts_.find(n); it != node_counts_.end()) return it->second;
    const std::size_t count = 1 + count_nodes(n / 2) + count_nodes(n - n / 2);
    node_counts_[n] = count;
    return count;
  }

  // Read-only after count_nodes(root size): safe from parallel subtrees.
  std::size_t subtree_nodes(std::size_t n) const { return n <= leaf_size_ ? 1 : node_counts_.at(n); }

  void build_subtree(std::vector<Node>& nodes, std::size_t index, std::size_t begin, std::size_t end) {
    Node& node = nodes[index];
    node.begin = static_cast<std::uint32_t>(begin);
    node.end = static_cast<std::uint32_t>(end);
    const std::size_t n = end - begin;
    if (n <= leaf_size_) {
      finish_leaf(node);
      return;
    }
    split_at_median(begin, end);
    const std::size_t mid = begin + n / 2;
    const std::size_t right = index + 1 + subtree_nodes(n / 2);
    node.right = static_cast<std::uint32_t>(right);
    auto left_task = [&] { build_subtree(nodes, index + 1, begin, mid); };
    auto right_task = [&] { build_subtree(nodes, right, mid, end); };
    if (n >= parallel_build_threshold)
      tbb::parallel_invoke(left_task, right_task);
    else {
      left_task();
      right_task();
    }
    finish_internal(node, nodes[index + 1], nodes[right]);
  }

  void split_at_median(std::size_t begin, std::size_t end) {
    Eigen::AlignedBox3d box;
    for (std::size_t i = begin; i < end; ++i) box.extend(centroids_[order_[i]]);
    int axis = 0;
    box.sizes().maxCoeff(&axis);
    // Ties broken by index: a strict order makes the split unique.
    std::nth_element(order_.begin() + begin, order_.begin() + begin + (end - begin) / 2, order_.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y) {
                       const double cx = centroids_[x][axis], cy = centroids_[y][axis];
                       return cx < cy || (cx == cy && x < y);
                     });
  }

  void finish_leaf(Node& node) const {
    double area = 0.0;
    Vec3d weighted = Vec3d::Zero();
    for (std::uint32_t i = node.begin; i < node.end; ++i) {
      const Corners& t = triangles_[order_[i]];
      const double a = 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
      area += a;
      weighted += a * centroids_[order_[i]];
    }
    node.area = area;
    node.center = area > 0.0 ? Vec3d(weighted / area) : centroids_[order_[node.begin]];
    for (std::uint32_t i = node.begin; i < node.end; ++i) {
      const Corners& t = triangles_[order_[i]];
      add_triangle_moments(t, node.center, node);
      for (const Vec3d* p : {&t.a, &t.b, &t.c})
        node.radius = std::max(node.radius, (*p - node.center).norm());
    }
  }

  void finish_internal(Node& node, const Node& left, const Node& right) const {
    node.area = left.area + right.area;
    node.center = node.area > 0.0 ? Vec3d((left.area * left.center + right.area * right.center) / node.area)
                                  : Vec3d(0.5 * (left.center + right.center));
    for (const Node* child : {&left, &right}) add_child_moments(*child, node.center, node);
    // The exact radius rather than the bound from the children's: tighter
    // spheres let more queries stop at this node.
    double radius_squared = 0.0;
    for (std::uint32_t i = node.begin; i < node.end; ++i) {
      const Corners& t = triangles_[order_[i]];
      for (const Vec3d* p : {&t.a, &t.b, &t.c})
        radius_squared = std::max(radius_squared, (*p - node.center).squaredNorm());
    }
    node.radius = std::sqrt(radius_squared);
  }

  const std::vector<Corners>& triangles_;
  std::size_t leaf_size_;
  std::vector<std::uint32_t> order_;
  std::vector<Vec3d> centroids_;
  std::unordered_map<std::size_t, std::size_t> node_counts_;
};

std::vector<Corners> non_degenerate_triangles(const TriangleSoup& soup) {
  std::vector<Corners> triangles;
  triangles.reserve(soup.triangles.size());
  for (const Triangle& t : soup.triangles) {
    Corners c{soup.positions[t[0]], soup.positions[t[1]], soup.positions[t[2]]};
    if ((c.b - c.a).cross(c.c - c.a).squaredNorm() > 0.0) triangles.push_back(c);
  }
  return triangles;
}

}  // namespace

WindingNumberTree::WindingNumberTree(const TriangleSoup& soup, const WindingNumberOptions& options)
    : options_(options) {
  if (!(options_.beta > 0.0)) throw std::invalid_argument("winding number beta must be positive");
  options_.leaf_size = std::max(options_.leaf_size, 1);
  std::vector<Corners> triangles = non_degenerate_triangles(soup);
  if (triangles.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("too many triangles for a winding number tree");
  const std::vector<std::uint32_t> order =
      TreeBuilder(triangles, static_cast<std::size_t>(options_.leaf_size)).build(nodes_);
  triangles_.reserve(order.size());
  for (std::uint32_t i : order) triangles_.push_back(triangles[i]);
}

// Order 0, 1 and 2 terms of the Taylor expansion of the dipole kernel
// (x - q) / |x - q|^3 about the node centre (Barill et al. 2018, eq. 13-15).
double WindingNumberTree::evaluate_node_expansion(const Node& node, const Vec3d& q) const {
  const Vec3d r = node.center - q;
  const double inv_r = 1.0 / r.norm();
  const double inv3 = inv_r * inv_r * inv_r, inv5 = inv3 * inv_r * inv_r, inv7 = inv5 * inv_r * inv_r;
  const double order0 = r.dot(node.normal_sum) * inv3;
  const double order1 = node.first.trace() * inv3 - 3.0 * r.dot(node.first * r) * inv5;
  // d[s*3 + j] holds the symmetric pair s = (i, k) and normal component j.
  const auto& d = node.second;
  double dot_r[6];  // sum_j r_j D_ikj for each pair (i, k)
  for (int s = 0; s < 6; ++s) dot_r[s] = r[0] * d[3 * s] + r[1] * d[3 * s + 1] + r[2] * d[3 * s + 2];
  const double contract_ii = dot_r[0] + dot_r[3] + dot_r[5];
  const double contract_all =
      r[0] * r[0] * dot_r[0] + r[1] * r[1] * dot_r[3] + r[2] * r[2] * dot_r[5] +
      2.0 * (r[0] * r[1] * dot_r[1] + r[0] * r[2] * dot_r[2] + r[1] * r[2] * dot_r[4]);
  // sum_ik r_k D_iki
  const double contract_ik =
      r[0] * (d[0] + d[4] + d[8]) + r[1] * (d[3] + d[10] + d[14]) + r[2] * (d[6] + d[13] + d[17]);
  const double order2 = 0.5 * (-3.0 * inv5 * (2.0 * contract_ik + contract_ii) + 15.0 * inv7 * contract_all);
  return (order0 + order1 + order2) * inv_four_pi;
}

double WindingNumberTree::evaluate(const Vec3d& q) const {
  if (nodes_.empty()) return 0.0;
  // Depth is at most log2(n) + 1 for median splits: 64 entries suffice for 2^32 triangles.
  std::array<std::uint32_t, 64> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  double sum = 0.0;
  double solid_angles = 0.0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if ((q - node.center).squaredNorm() > options_.beta * options_.beta * node.radius * node.radius) {
      sum += evaluate_node_expansion(node, q);
    } else if (node.right == 0) {
      for (std::uint32_t i = node.begin; i < node.end; ++i)
        solid_angles += signed_solid_angle(triangles_[i].a, triangles_[i].b, triangles_[i].c, q);
    } else {
      stack[top++] = node.right;
      stack[top++] = static_cast<std::uint32_t>(&node - nodes_.data()) + 1;
    }
  }
  return sum + solid_angles * inv_four_pi;
}

std::vector<double> WindingNumberTree::evaluate(std::span<const Vec3d> queries) const {
  std::vector<double> result(queries.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, queries.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        result[i] = evaluate(queries[i]);
                    });
  return result;
}

}  // namespace mr
