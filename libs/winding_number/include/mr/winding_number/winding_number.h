#pragma once
// Generalized winding number of a triangle soup (Jacobson et al. 2013): the
// sum of the signed solid angles of the triangles seen from a query point,
// divided by 4*pi. It is 1 inside and 0 outside a closed outward-oriented
// surface, counts overlaps (2 inside two overlapping solids) and degrades
// gracefully on open, self-intersecting and inconsistently oriented soups,
// which is why "w > 1/2" is the robust inside test for broken inputs.

#include <mr/core/triangle_soup.h>

#include <cstdint>
#include <span>
#include <vector>

namespace mr {

/// Signed solid angle of triangle (a, b, c) seen from q, in [-2*pi, 2*pi]
/// (Van Oosterom and Strackee 1983). Positive when q sees the back side, i.e.
/// when q is on the side opposite to the normal (b - a) x (c - a). Returns 0 for
/// degenerate (zero-area) triangles and when q coincides with a corner; never NaN
/// for finite input.
double signed_solid_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& q);

/// Winding number of `soup` at q by direct summation over every triangle: O(n).
/// The reference the fast evaluation is tested against.
double winding_number_exact(const TriangleSoup& soup, const Vec3d& q);

struct WindingNumberOptions {
  /// Accuracy: a node's expansion is used when the query is farther than
  /// beta times the node's radius from its centre. Larger is more accurate and slower.
  double beta = 2.0;
  /// Triangles per leaf, evaluated exactly.
  int leaf_size = 8;
};

/// Fast winding numbers (Barill et al. 2018): a bounding volume hierarchy over
/// the triangles storing per node the order-0, order-1 and order-2 Taylor
/// terms of the dipole field, so that far clusters cost O(1). Built once,
/// then immutable: concurrent evaluate() calls are safe. The tree copies the
/// geometry it needs; the soup may be destroyed after construction.
class WindingNumberTree {
 public:
  explicit WindingNumberTree(const TriangleSoup& soup, const WindingNumberOptions& options = {});

  double evaluate(const Vec3d& q) const;
  /// Evaluates every query in parallel; each result is the same as evaluate(q)
  /// whatever the number of threads.
  std::vector<double> evaluate(std::span<const Vec3d> queries) const;

  std::size_t num_triangles() const { return triangles_.size(); }
  std::size_t num_nodes() const { return nodes_.size(); }

  struct Corners {
    Vec3d a, b, c;
  };
  /// Taylor coefficients of one cluster of triangles about its centre.
  struct Node {
    Vec3d center = Vec3d::Zero();
    double radius = 0.0;  ///< bounds every corner's distance to center
    double area = 0.0;
    Vec3d normal_sum = Vec3d::Zero();                 ///< order 0: sum of area * normal
    Eigen::Matrix3d first = Eigen::Matrix3d::Zero();  ///< order 1: sum of int (x-c)_i n_j
    std::array<double, 18> second{};                  ///< order 2: int (x-c)_i (x-c)_k n_j, (ik) symmetric
    std::uint32_t begin = 0, end = 0;                 ///< triangle range
    std::uint32_t right = 0;                          ///< right child; left child is this + 1; 0 = leaf
  };

 private:
  double evaluate_node_expansion(const Node& node, const Vec3d& q) const;

  WindingNumberOptions options_;
  std::vector<Corners> triangles_;  ///< non-degenerate triangles, in tree order
  std::vector<Node> nodes_;         ///< pre-order; nodes_[0] is the root
};

}  // namespace mr
