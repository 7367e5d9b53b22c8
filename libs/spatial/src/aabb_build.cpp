// Top-down median-split build of the AABB tree. Splitting at the median
// count makes the size of every subtree a function of its triangle count
// alone, so both halves can be built in parallel straight into their final
// slots of the depth-first node array: parallel and deterministic.

#include <mr/core/errors.h>
#include <mr/spatial/aabb_tree.h>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mr::spatial {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr std::uint32_t kParallelBuildSize = 8192;

// Subtree sizes (node counts) by depth. At depth k every range holds
// either `small` or `small + 1` triangles, so two numbers a level suffice.
class SubtreeSizes {
 public:
  explicit SubtreeSizes(std::uint32_t n) {
    std::uint32_t small = n;
    for (;;) {
      levels_.push_back({small, 0, 0});
      if (small + 1 <= kLeafSize) break;
      small /= 2;
    }
    for (std::size_t d = levels_.size(); d-- > 0;) {
      levels_[d].nodes_small = count(d, levels_[d].small);
      levels_[d].nodes_large = count(d, levels_[d].small + 1);
    }
  }
  /// Nodes of the subtree over `size` triangles at `depth`.
  std::uint32_t nodes(std::size_t depth, std::uint32_t size) const {
    const Level& level = levels_[depth];
    return size == level.small ? level.nodes_small : level.nodes_large;
  }

 private:
  struct Level {
    std::uint32_t small;
    std::uint32_t nodes_small;
    std::uint32_t nodes_large;
  };
  std::uint32_t count(std::size_t depth, std::uint32_t size) const {
    if (size <= kLeafSize) return 1;
    return 1 + nodes(depth + 1, size / 2) + nodes(depth + 1, size - size / 2);
  }
  std::vector<Level> levels_;
};

void grow(AabbBox& box, const Vec3d& p) {
  box.lo = box.lo.cwiseMin(p);
  box.hi = box.hi.cwiseMax(p);
}

void grow(AabbTree::Node& node, const AabbTree::Node& child) {
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = std::min(node.lo[k], child.lo[k]);
    node.hi[k] = std::max(node.hi[k], child.hi[k]);
  }
}

void validate(const TriangleSoup& soup) {
  if (soup.triangles.size() >= kNoTriangle) throw UsageError("AabbTree: too many triangles");
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    for (Index v : soup.triangles[t]) {
      if (v >= soup.positions.size()) {
        throw UsageError("AabbTree: triangle " + std::to_string(t) + " has vertex index " +
                         std::to_string(v) + " out of range");
      }
      if (!soup.positions[v].allFinite()) {
        throw UsageError("AabbTree: vertex " + std::to_string(v) + " has a non-finite coordinate");
      }
    }
  }
}

}  // namespace

class AabbBuilder {
 public:
  AabbBuilder(const TriangleSoup& soup, AabbTree& tree) : soup_(soup), tree_(tree) {}

  void build() {
    const auto n = static_cast<std::uint32_t>(soup_.triangles.size());
    if (n == 0) return;
    prepare_primitives(n);
    const SubtreeSizes sizes(n);
    sizes_ = &sizes;
    tree_.nodes_.resize(sizes.nodes(0, n));
    AabbBox centroids;
    for (const Primitive& primitive : order_) grow(centroids, primitive.centroid);
    build_node(0, 0, n, 0, centroids);
    store_triangles(n);
  }

 private:
  void prepare_primitives(std::uint32_t n) {
    boxes_.resize(n);
    order_.resize(n);
    tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t t) {
      AabbBox box;
      for (Index v : soup_.triangles[t]) grow(box, soup_.positions[v]);
      boxes_[t] = box;
      order_[t] = {0.5 * (box.lo + box.hi), t};
    });
  }

  // `centroids` bounds the centroids of the range (not tightly: each split
  // only clips the parent's bounds at the median, which saves a pass).
  void build_node(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::size_t depth,
                  const AabbBox& centroids) {
    AabbTree::Node& out = tree_.nodes_[node];
    const std::uint32_t n = end - begin;
    if (n <= kLeafSize) {
      make_leaf(out, begin, end);
      return;
    }
    int axis = 0;
    (centroids.hi - centroids.lo).maxCoeff(&axis);
    const std::uint32_t mid = begin + n / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [axis](const Primitive& i, const Primitive& j) {
                       const double ci = i.centroid[axis];
                       const double cj = j.centroid[axis];
                       return ci < cj || (ci == cj && i.id < j.id);
                     });
    const std::uint32_t left = node + 1;
    const std::uint32_t right = left + sizes_->nodes(depth + 1, mid - begin);
    AabbBox left_centroids = centroids;
    AabbBox right_centroids = centroids;
    left_centroids.hi[axis] = right_centroids.lo[axis] = order_[mid].centroid[axis];
    if (n >= kParallelBuildSize) {
      tbb::parallel_invoke([&] { build_node(left, begin, mid, depth + 1, left_centroids); },
                           [&] { build_node(right, mid, end, depth + 1, right_centroids); });
    } else {
      build_node(left, begin, mid, depth + 1, left_centroids);
      build_node(right, mid, end, depth + 1, right_centroids);
    }
    out = tree_.nodes_[left];
    grow(out, tree_.nodes_[right]);
    out.first_or_right = right;
    out.count = 0;
  }

  void make_leaf(AabbTree::Node& out, std::uint32_t begin, std::uint32_t end) const {
    AabbBox box;
    for (std::uint32_t s = begin; s < end; ++s) {
      box.lo = box.lo.cwiseMin(boxes_[order_[s].id].lo);
      box.hi = box.hi.cwiseMax(boxes_[order_[s].id].hi);
    }
    for (int k = 0; k < 3; ++k) {
      out.lo[k] = box.lo[k];
      out.hi[k] = box.hi[k];
    }
    out.first_or_right = begin;
    out.count = end - begin;
  }

  void store_triangles(std::uint32_t n) {
    tree_.corners_.resize(std::size_t{3} * n);
    tree_.triangle_ids_.resize(n);
    tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t slot) {
      const std::uint32_t t = order_[slot].id;
      tree_.triangle_ids_[slot] = t;
      for (int k = 0; k < 3; ++k)
        tree_.corners_[3 * std::size_t{slot} + k] = soup_.positions[soup_.triangles[t][k]];
    });
  }

  const TriangleSoup& soup_;
  AabbTree& tree_;
  struct Primitive {
    Vec3d centroid;
    std::uint32_t id;
  };
  const SubtreeSizes* sizes_ = nullptr;
  std::vector<AabbBox> boxes_;
  std::vector<Primitive> order_;  // permuted into leaf order by the build
};

AabbTree::AabbTree(const TriangleSoup& soup) {
  validate(soup);
  AabbBuilder(soup, *this).build();
}

}  // namespace mr::spatial
