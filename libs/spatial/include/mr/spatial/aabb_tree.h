#pragma once
// Bounding volume hierarchy (axis-aligned boxes) over a triangle soup, for
// closest-point and "anything within r" queries. The tree copies the
// triangles it needs, so the soup may go away after construction. All
// queries are const and keep no caches: any number of threads may query one
// tree at once.

#include <mr/core/triangle_soup.h>
#include <mr/core/types.h>

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace mr::spatial {

inline constexpr std::uint32_t kNoTriangle = std::numeric_limits<std::uint32_t>::max();

struct ClosestHit {
  std::uint32_t triangle = kNoTriangle;  ///< index into the soup's triangles
  Vec3d point = Vec3d::Zero();
  double squared_distance = std::numeric_limits<double>::infinity();
  bool found() const { return triangle != kNoTriangle; }
};

struct AabbBox {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  Vec3d hi = Vec3d::Constant(-std::numeric_limits<double>::infinity());
};

struct AabbTreeOptions {
  /// Cut triangles much longer than the soup's extent / 128 into pieces
  /// (longest-edge bisection, a few MB of them at most), each with its own
  /// box in the tree; queries still measure the whole triangle. Distance
  /// queries near a soup of huge triangles or long slivers then visit only
  /// the pieces nearby instead of every triangle whose box holds the point.
  /// Box queries (triangles_in_box) gain little and pay to drop the repeats.
  bool cut_large_triangles = false;
};

class AabbTree {
 public:
  /// An empty tree: every query finds nothing.
  AabbTree() = default;
  /// Builds over every triangle of `soup`, degenerate ones included; the
  /// build is parallel (TBB) and deterministic. Throws mr::UsageError on an
  /// index out of range or a non-finite coordinate of a used vertex.
  explicit AabbTree(const TriangleSoup& soup, const AabbTreeOptions& options = {});

  std::size_t num_triangles() const { return triangle_count_; }
  bool empty() const { return triangle_ids_.empty(); }
  /// Box of all triangles (empty box for an empty tree).
  AabbBox bounds() const;

  /// Nearest triangle, its closest point and the squared distance. Ties go to
  /// whichever triangle the traversal meets first (deterministic).
  ClosestHit closest(const Vec3d& p) const;
  /// As closest(), but triangles farther than max_distance are ignored
  /// (returns a hit with found() == false when there is none).
  ClosestHit closest_within(const Vec3d& p, double max_distance) const;
  double squared_distance(const Vec3d& p) const { return closest(p).squared_distance; }

  /// The triangles (soup indices, increasing) with a point at distance <= r from p.
  std::vector<std::uint32_t> triangles_within(const Vec3d& p, double r) const;

  /// Appends to `out` the triangles (soup indices, each once) whose
  /// bounding box, or for a triangle the build cut into pieces the box of a
  /// piece, meets the closed box [lo, hi]: in tree order, or increasing
  /// when the tree has pieces. Boxes are compared exactly, so every triangle
  /// that meets the box is among them.
  void triangles_in_box(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const;

  /// True when some triangle has a point at distance <= r from p. Stops at
  /// the first such triangle.
  bool any_within(const Vec3d& p, double r) const;

  /// Squared distance from p, computed only as far as needed: returns s with
  ///  - s <= accept_sq and s >= true squared distance, if the true squared
  ///    distance is <= accept_sq (stops at the first triangle closer than that);
  ///  - the exact squared distance, if it lies in (accept_sq, cap_sq];
  ///  - +infinity, if it exceeds cap_sq.
  /// So s is always an upper bound of the true value, and exact when it matters.
  double squared_distance_bounded(const Vec3d& p, double accept_sq, double cap_sq) const;
  /// squared_distance_bounded and the slot of the triangle that gave it
  /// (kNoSlot with +infinity).
  struct BoundedHit {
    double squared_distance;
    std::uint32_t slot;
  };
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  BoundedHit nearest_bounded(const Vec3d& p, double accept_sq, double cap_sq) const;
  /// Whether every point of `points` lies within squared distance r_sq of
  /// the triangle in `slot` (a slot from nearest_bounded).
  bool slot_near_all(std::uint32_t slot, std::span<const Vec3d> points, double r_sq) const;

  /// True when one single triangle has every point of `points` within
  /// squared distance r_sq. Since the distance to a triangle is a convex
  /// function, the whole convex hull of the points is then within that
  /// distance of the triangle. `points` must not be empty.
  bool one_triangle_near_all(std::span<const Vec3d> points, double r_sq) const;

  struct Node {
    double lo[3];
    double hi[3];
    std::uint32_t first_or_right;  ///< leaf: first triangle slot; inner: right child
    std::uint32_t count;           ///< leaf: number of triangles; inner: 0 (left child = this + 1)
  };

 private:
  template <class Visitor>
  void traverse(const Vec3d& p, double& bound_sq, Visitor&& visit) const;

  /// Whether some triangle was cut into pieces (aabb_build.cpp): then one
  /// triangle fills several slots.
  bool has_pieces() const { return triangle_ids_.size() != triangle_count_; }
  /// Calls visit(slot) for every slot whose box (a piece's box, with pieces)
  /// meets the closed box [lo, hi], until it returns false.
  template <class Visitor>
  void for_each_slot_in_box(const Vec3d& lo, const Vec3d& hi, Visitor&& visit) const;

  std::vector<Node> nodes_;                  // depth-first order, root first
  std::vector<Vec3d> corners_;               // 3 per slot (its whole triangle's), in leaf order
  std::vector<std::uint32_t> triangle_ids_;  // soup index of each slot
  std::vector<AabbBox> slot_boxes_;          // box of each slot's piece; empty without pieces
  AabbBox slot_box(std::uint32_t slot) const;
  std::size_t triangle_count_ = 0;

  friend class AabbBuilder;
  friend class LocalTriangles;
};

/// The triangles of a tree that meet a box, each once, for many queries
/// near one place (an envelope test bisecting one face): searched one by
/// one they answer every query whose search ball lies in the box as the
/// tree does, without a descent from the root per query. Slots are the
/// tree's (AabbTree::slot_near_all takes them). A view: the tree must outlive it.
class LocalTriangles {
 public:
  /// The triangles of `tree` whose box meets the closed box [lo, hi]
  /// (compared exactly); none, and overflowed(), when more than `max_count` do.
  LocalTriangles(const AabbTree& tree, const Vec3d& lo, const Vec3d& hi, std::size_t max_count);

  bool overflowed() const { return overflowed_; }
  std::size_t size() const { return slots_.size(); }

  /// AabbTree::nearest_bounded, for p whose ball of squared radius cap_sq lies in the box.
  AabbTree::BoundedHit nearest_bounded(const Vec3d& p, double accept_sq, double cap_sq) const;
  /// AabbTree::one_triangle_near_all, for points whose balls of squared
  /// radius r_sq lie in the box.
  bool one_triangle_near_all(std::span<const Vec3d> points, double r_sq) const;

 private:
  const AabbTree* tree_;
  std::vector<std::uint32_t> slots_;  ///< one slot per triangle
  std::vector<AabbBox> boxes_;        ///< each slot's whole triangle's box
  bool overflowed_ = false;
};

inline AabbBox AabbTree::slot_box(std::uint32_t slot) const {
  if (!slot_boxes_.empty()) return slot_boxes_[slot];
  const Vec3d* c = &corners_[3 * std::size_t{slot}];
  return {c[0].cwiseMin(c[1]).cwiseMin(c[2]), c[0].cwiseMax(c[1]).cwiseMax(c[2])};
}

}  // namespace mr::spatial
