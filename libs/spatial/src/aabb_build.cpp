// Top-down median-split build of the AABB tree. Splitting at the median
// count makes the size of every subtree a function of its triangle count
// alone, so both halves can be built in parallel straight into their final
// slots of the depth-first node array: parallel and deterministic.
//
// The tree is built over pieces of triangles, one per triangle unless
// AabbTreeOptions::cut_large_triangles: then a triangle much larger than the
// tree's boxes should be (a soup's triangles span the whole model) is cut by
// longest-edge bisection into pieces whose boxes cover it, so a query near
// one end no longer visits it from everywhere in its box. Every piece keeps
// its triangle's corners: distances are to the whole triangle, and only the
// pruning sees the pieces.

#include <mr/core/errors.h>
#include <mr/spatial/aabb_tree.h>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace mr::spatial {

namespace {

constexpr std::uint32_t kLeafSize = 4;
constexpr std::uint32_t kParallelBuildSize = 8192;

// AabbTreeOptions::cut_large_triangles: pieces are cut until their longest
// edge is at most the tree's extent over kPiecesAcross (or twice that, and
// so on, until all fit in the budget: the triangles plus kExtraPieces).
// 2^16 extra pieces cost a tetrahedralize run 6 to 13 MB (two such trees)
// and made small models slower, not faster (suzanne 5.1 -> 4.8 s user with
// 2^14); 2^12 made trimesh/soup, all huge triangles, 5% slower.
constexpr double kPiecesAcross = 128.0;
constexpr std::size_t kExtraPieces = std::size_t{1} << 14;
// How much a piece's box grows, relative to the triangle's largest coordinate.
constexpr double kPieceBoxMargin = 1e-12;
// The deepest bisection: 2^20 pieces would exceed any budget anyway.
constexpr int kMaxBisections = 20;

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

double longest_edge(const std::array<Vec3d, 3>& c) {
  return std::sqrt(
      std::max({(c[1] - c[0]).squaredNorm(), (c[2] - c[1]).squaredNorm(), (c[0] - c[2]).squaredNorm()}));
}

// The two halves of c split at the midpoint of its longest edge (the first
// longest on ties, so the cut is fixed).
std::array<std::array<Vec3d, 3>, 2> bisected(const std::array<Vec3d, 3>& c) {
  int longest = 0;
  double best = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double length = (c[(i + 1) % 3] - c[i]).squaredNorm();
    if (length > best) best = length, longest = i;
  }
  const Vec3d& a = c[longest];
  const Vec3d& b = c[(longest + 1) % 3];
  const Vec3d& apex = c[(longest + 2) % 3];
  const Vec3d middle = 0.5 * (a + b);
  return {{{a, middle, apex}, {middle, b, apex}}};
}

// Calls emit(piece) for every piece of triangle c, cut by longest-edge
// bisection until the longest edge is at most `size`, or for c itself when
// it already is; stops as soon as emit returns false. False if it stopped.
template <class Emit>
bool cut_into_pieces(const std::array<Vec3d, 3>& c, double size, int depth, Emit&& emit) {
  if (depth == kMaxBisections || longest_edge(c) <= size) return emit(c);
  for (const std::array<Vec3d, 3>& half : bisected(c))
    if (!cut_into_pieces(half, size, depth + 1, emit)) return false;
  return true;
}

// The number of pieces cut_into_pieces makes of c, or some number above
// `limit` when that is more.
std::size_t count_pieces(const std::array<Vec3d, 3>& c, double size, std::size_t limit) {
  std::size_t pieces = 0;
  cut_into_pieces(c, size, 0, [&](const std::array<Vec3d, 3>&) { return ++pieces <= limit; });
  return pieces;
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
  AabbBuilder(const TriangleSoup& soup, const AabbTreeOptions& options, AabbTree& tree)
      : soup_(soup), options_(options), tree_(tree) {}

  void build() {
    const auto n = static_cast<std::uint32_t>(soup_.triangles.size());
    if (n == 0) return;
    tree_.triangle_count_ = n;
    prepare_primitives(n);
    const auto slots = static_cast<std::uint32_t>(order_.size());
    const SubtreeSizes sizes(slots);
    sizes_ = &sizes;
    tree_.nodes_.resize(sizes.nodes(0, slots));
    AabbBox centroids;
    for (const Primitive& primitive : order_) grow(centroids, primitive.centroid);
    build_node(0, 0, slots, 0, centroids);
    store_slots(slots);
  }

 private:
  std::array<Vec3d, 3> corners(std::uint32_t t) const {
    const Triangle& f = soup_.triangles[t];
    return {soup_.positions[f[0]], soup_.positions[f[1]], soup_.positions[f[2]]};
  }

  // The longest edge a piece may have, and per triangle its number of
  // pieces: the tree's extent / kPiecesAcross, doubled until the pieces fit
  // the budget (a count stops as soon as it is over). Infinite (one piece
  // each) without cutting.
  double piece_size(std::vector<std::size_t>& counts) const {
    std::fill(counts.begin(), counts.end(), std::size_t{1});
    if (!options_.cut_large_triangles) return std::numeric_limits<double>::infinity();
    AabbBox all;
    for (const Triangle& f : soup_.triangles)
      for (Index v : f) grow(all, soup_.positions[v]);
    const double extent = (all.hi - all.lo).maxCoeff();
    const std::size_t budget = counts.size() + kExtraPieces;
    for (double size = extent / kPiecesAcross;; size *= 2.0) {
      // Pieces as long as the extent: a few per triangle, over budget or not.
      const bool last = !(size < extent);
      std::size_t total = 0;
      for (std::size_t t = 0; t < counts.size() && (last || total <= budget); ++t) {
        const std::size_t limit = last ? std::numeric_limits<std::size_t>::max() : budget - total;
        counts[t] = count_pieces(corners(static_cast<std::uint32_t>(t)), size, limit);
        total += counts[t];
      }
      if (last || total <= budget) return size;
    }
  }

  // One primitive per piece, pieces of one triangle in a row, triangles in
  // order: the same list whatever the thread count.
  void prepare_primitives(std::uint32_t n) {
    std::vector<std::size_t> counts(n);
    const double size = piece_size(counts);
    std::vector<std::size_t> first(n + 1, 0);
    for (std::uint32_t t = 0; t < n; ++t) first[t + 1] = first[t] + counts[t];
    boxes_.resize(first[n]);
    order_.resize(first[n]);
    tbb::parallel_for(std::uint32_t{0}, n, [&](std::uint32_t t) {
      const std::array<Vec3d, 3> c = corners(t);
      AabbBox whole;
      for (const Vec3d& p : c) grow(whole, p);
      // Rounded midpoints drift by a few units in the last place per cut:
      // far less than this margin, so the pieces' boxes cover the triangle.
      const double margin =
          kPieceBoxMargin * std::max(whole.lo.cwiseAbs().maxCoeff(), whole.hi.cwiseAbs().maxCoeff());
      std::size_t slot = first[t];
      cut_into_pieces(c, size, 0, [&](const std::array<Vec3d, 3>& piece) {
        AabbBox box = whole;
        if (counts[t] > 1) {
          AabbBox own;
          for (const Vec3d& p : piece) grow(own, p);
          box.lo = whole.lo.cwiseMax(own.lo - Vec3d::Constant(margin));
          box.hi = whole.hi.cwiseMin(own.hi + Vec3d::Constant(margin));
        }
        boxes_[slot] = box;
        order_[slot] = {0.5 * (box.lo + box.hi), static_cast<std::uint32_t>(slot), t};
        ++slot;
        return true;
      });
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
                       return ci < cj || (ci == cj && i.piece < j.piece);
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
      box.lo = box.lo.cwiseMin(boxes_[order_[s].piece].lo);
      box.hi = box.hi.cwiseMax(boxes_[order_[s].piece].hi);
    }
    for (int k = 0; k < 3; ++k) {
      out.lo[k] = box.lo[k];
      out.hi[k] = box.hi[k];
    }
    out.first_or_right = begin;
    out.count = end - begin;
  }

  void store_slots(std::uint32_t slots) {
    tree_.corners_.resize(std::size_t{3} * slots);
    tree_.triangle_ids_.resize(slots);
    if (slots != tree_.triangle_count_) tree_.slot_boxes_.resize(slots);
    tbb::parallel_for(std::uint32_t{0}, slots, [&](std::uint32_t slot) {
      const Primitive& primitive = order_[slot];
      tree_.triangle_ids_[slot] = primitive.triangle;
      if (!tree_.slot_boxes_.empty()) tree_.slot_boxes_[slot] = boxes_[primitive.piece];
      for (int k = 0; k < 3; ++k)
        tree_.corners_[3 * std::size_t{slot} + k] = soup_.positions[soup_.triangles[primitive.triangle][k]];
    });
  }

  const TriangleSoup& soup_;
  const AabbTreeOptions& options_;
  AabbTree& tree_;
  struct Primitive {
    Vec3d centroid;
    std::uint32_t piece;     ///< index into boxes_
    std::uint32_t triangle;  ///< the soup's
  };
  const SubtreeSizes* sizes_ = nullptr;
  std::vector<AabbBox> boxes_;
  std::vector<Primitive> order_;  // permuted into leaf order by the build
};

AabbTree::AabbTree(const TriangleSoup& soup, const AabbTreeOptions& options) {
  validate(soup);
  AabbBuilder(soup, options, *this).build();
}

}  // namespace mr::spatial
