// Queries of the AABB tree: one depth-first traversal, nearer child first,
// pruned by a squared-distance bound that the visitor may shrink.

#include <mr/spatial/aabb_tree.h>
#include <mr/spatial/triangle_distance.h>

#include <algorithm>
#include <limits>
#include <span>
#include <utility>

namespace mr::spatial {

namespace {

double box_squared_distance(const AabbTree::Node& node, const Vec3d& p) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double below = node.lo[k] - p[k];
    const double above = p[k] - node.hi[k];
    const double gap = std::max({below, above, 0.0});
    sum += gap * gap;
  }
  return sum;
}

// Squared distance from p to a box (a triangle's: a lower bound of its
// distance to the triangle, for a few operations).
double box_squared_distance(const AabbBox& box, const Vec3d& p) {
  return (box.lo - p).cwiseMax(p - box.hi).cwiseMax(0.0).squaredNorm();
}

AabbBox triangle_box(const Vec3d* c) {
  return {c[0].cwiseMin(c[1]).cwiseMin(c[2]), c[0].cwiseMax(c[1]).cwiseMax(c[2])};
}

// Whether every point lies within squared distance r_sq of triangle c[0..2]
// whose box is `box`: the boxes first (most triangles near one point are far
// from another), then the exact distances, the last points first.
bool triangle_near_all(const Vec3d* c, const AabbBox& box, std::span<const Vec3d> points, double r_sq) {
  const auto box_near = [&](const Vec3d& p) { return box_squared_distance(box, p) <= r_sq; };
  if (!std::all_of(points.begin(), points.end(), box_near)) return false;
  return std::all_of(points.rbegin(), points.rend(), [&](const Vec3d& p) {
    return squared_distance_to_triangle(p, c[0], c[1], c[2]) <= r_sq;
  });
}

// The squared distance from p to triangle c[0..2] if it is at most
// bound_sq, else +infinity; `box` (the triangle's, or a piece's) is tried first.
double distance_sq_within(const Vec3d* c, const AabbBox& box, const Vec3d& p, double bound_sq) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (box_squared_distance(box, p) > bound_sq) return kInfinity;
  const double d_sq = squared_distance_to_triangle(p, c[0], c[1], c[2]);
  return d_sq <= bound_sq ? d_sq : kInfinity;
}

// Drops the repeats (pieces of one triangle) from out[from, end), sorted.
void keep_each_once(std::vector<std::uint32_t>& out, std::size_t from) {
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(from), out.end());
  out.erase(std::unique(out.begin() + static_cast<std::ptrdiff_t>(from), out.end()), out.end());
}

// A median-split tree over fewer than 2^32 triangles is at most 32 levels deep.
constexpr int kMaxStack = 64;

}  // namespace

AabbBox AabbTree::bounds() const {
  AabbBox box;
  if (nodes_.empty()) return box;
  box.lo = Vec3d(nodes_[0].lo[0], nodes_[0].lo[1], nodes_[0].lo[2]);
  box.hi = Vec3d(nodes_[0].hi[0], nodes_[0].hi[1], nodes_[0].hi[2]);
  return box;
}

// Visits the triangle slots of every leaf whose box is within sqrt(bound_sq)
// of p; visit(slot) returns true to stop the whole traversal.
template <class Visitor>
void AabbTree::traverse(const Vec3d& p, double& bound_sq, Visitor&& visit) const {
  if (nodes_.empty() || box_squared_distance(nodes_[0], p) > bound_sq) return;
  struct Pending {
    std::uint32_t node;
    double squared_distance;
  };
  Pending stack[kMaxStack];
  int top = 0;
  std::uint32_t node = 0;
  for (;;) {
    const Node& current = nodes_[node];
    bool descend = false;
    if (current.count != 0) {
      const std::uint32_t end = current.first_or_right + current.count;
      for (std::uint32_t slot = current.first_or_right; slot < end; ++slot) {
        if (visit(slot)) return;
      }
    } else {
      std::uint32_t near = node + 1;
      std::uint32_t far = current.first_or_right;
      double near_sq = box_squared_distance(nodes_[near], p);
      double far_sq = box_squared_distance(nodes_[far], p);
      if (far_sq < near_sq) {
        std::swap(near, far);
        std::swap(near_sq, far_sq);
      }
      if (near_sq <= bound_sq) {
        if (far_sq <= bound_sq) stack[top++] = {far, far_sq};
        node = near;
        descend = true;
      }
    }
    if (descend) continue;
    for (;;) {
      if (top == 0) return;
      const Pending next = stack[--top];
      if (next.squared_distance <= bound_sq) {
        node = next.node;
        break;
      }
    }
  }
}

ClosestHit AabbTree::closest(const Vec3d& p) const {
  return closest_within(p, std::numeric_limits<double>::infinity());
}

ClosestHit AabbTree::closest_within(const Vec3d& p, double max_distance) const {
  ClosestHit hit;
  if (!(max_distance >= 0.0)) return hit;
  double bound_sq = max_distance * max_distance;
  std::uint32_t best_slot = kNoTriangle;
  traverse(p, bound_sq, [&](std::uint32_t slot) {
    const Vec3d* c = &corners_[3 * std::size_t{slot}];
    const PointOnPrimitive q = closest_on_triangle(p, c[0], c[1], c[2]);
    if (q.squared_distance <= bound_sq &&
        (best_slot == kNoTriangle || q.squared_distance < hit.squared_distance)) {
      best_slot = slot;
      hit.point = q.point;
      hit.squared_distance = q.squared_distance;
      bound_sq = q.squared_distance;
    }
    return false;
  });
  if (best_slot != kNoTriangle) hit.triangle = triangle_ids_[best_slot];
  return hit;
}

std::vector<std::uint32_t> AabbTree::triangles_within(const Vec3d& p, double r) const {
  std::vector<std::uint32_t> found;
  if (!(r >= 0.0)) return found;
  double bound_sq = r * r;  // never shrinks: every triangle that near counts
  traverse(p, bound_sq, [&](std::uint32_t slot) {
    const Vec3d* c = &corners_[3 * std::size_t{slot}];
    if (squared_distance_to_triangle(p, c[0], c[1], c[2]) <= r * r) found.push_back(triangle_ids_[slot]);
    return false;
  });
  keep_each_once(found, 0);
  return found;
}

double AabbTree::squared_distance_bounded(const Vec3d& p, double accept_sq, double cap_sq) const {
  return nearest_bounded(p, accept_sq, cap_sq).squared_distance;
}

AabbTree::BoundedHit AabbTree::nearest_bounded(const Vec3d& p, double accept_sq, double cap_sq) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(cap_sq >= 0.0)) return {kInfinity, kNoSlot};
  double bound_sq = cap_sq;
  std::uint32_t found = kNoSlot;
  traverse(p, bound_sq, [&](std::uint32_t slot) {
    // The piece's own box first: a leaf's box holds four, and long
    // slivers in different directions leave most of it empty.
    const double d_sq = distance_sq_within(&corners_[3 * std::size_t{slot}], slot_box(slot), p, bound_sq);
    if (d_sq > bound_sq) return false;
    bound_sq = d_sq;
    found = slot;
    return d_sq <= accept_sq;
  });
  return found != kNoSlot ? BoundedHit{bound_sq, found} : BoundedHit{kInfinity, kNoSlot};
}

bool AabbTree::slot_near_all(std::uint32_t slot, std::span<const Vec3d> points, double r_sq) const {
  const Vec3d* c = &corners_[3 * std::size_t{slot}];
  return std::all_of(points.begin(), points.end(), [&](const Vec3d& p) {
    return squared_distance_to_triangle(p, c[0], c[1], c[2]) <= r_sq;
  });
}

bool AabbTree::one_triangle_near_all(std::span<const Vec3d> points, double r_sq) const {
  if (!(r_sq >= 0.0) || points.empty()) return false;
  double bound_sq = r_sq;  // never shrinks: every triangle near points[0] is a candidate
  bool found = false;
  std::uint32_t last_triangle = kNoTriangle;  // pieces of one triangle often come in a row
  traverse(points[0], bound_sq, [&](std::uint32_t slot) {
    if (std::exchange(last_triangle, triangle_ids_[slot]) == triangle_ids_[slot]) return false;
    const Vec3d* c = &corners_[3 * std::size_t{slot}];
    found = triangle_near_all(c, triangle_box(c), points, r_sq);
    return found;
  });
  return found;
}

template <class Visitor>
void AabbTree::for_each_slot_in_box(const Vec3d& lo, const Vec3d& hi, Visitor&& visit) const {
  const auto meets = [&](const Vec3d& box_lo, const Vec3d& box_hi) {
    return (box_lo.array() <= hi.array()).all() && (lo.array() <= box_hi.array()).all();
  };
  const auto node_meets = [&](const Node& node) {
    return meets(Vec3d(node.lo[0], node.lo[1], node.lo[2]), Vec3d(node.hi[0], node.hi[1], node.hi[2]));
  };
  if (nodes_.empty() || !node_meets(nodes_[0])) return;
  std::uint32_t stack[kMaxStack];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::uint32_t index = stack[--top];
    const Node& node = nodes_[index];
    if (node.count != 0) {
      for (std::uint32_t slot = node.first_or_right; slot < node.first_or_right + node.count; ++slot) {
        const AabbBox box = slot_box(slot);
        if (meets(box.lo, box.hi) && !visit(slot)) return;
      }
      continue;
    }
    for (const std::uint32_t child : {index + 1, node.first_or_right})
      if (node_meets(nodes_[child])) stack[top++] = child;
  }
}

void AabbTree::triangles_in_box(const Vec3d& lo, const Vec3d& hi, std::vector<std::uint32_t>& out) const {
  const std::size_t from = out.size();
  for_each_slot_in_box(lo, hi, [&](std::uint32_t slot) {
    out.push_back(triangle_ids_[slot]);
    return true;
  });
  if (has_pieces()) keep_each_once(out, from);
}

LocalTriangles::LocalTriangles(const AabbTree& tree, const Vec3d& lo, const Vec3d& hi, std::size_t max_count)
    : tree_(&tree) {
  // Pieces repeat a triangle: up to this many slots are gathered before
  // they are told apart.
  const std::size_t most_slots = 16 * max_count + 16;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> found;  // {triangle, slot}
  tree.for_each_slot_in_box(lo, hi, [&](std::uint32_t slot) {
    found.emplace_back(tree.triangle_ids_[slot], slot);
    return found.size() <= most_slots;
  });
  if (found.size() > most_slots) {
    overflowed_ = true;
    return;
  }
  // Pieces of one triangle: keep its first slot (distances are to the whole triangle).
  std::sort(found.begin(), found.end());
  const auto same_triangle = [](const auto& x, const auto& y) { return x.first == y.first; };
  found.erase(std::unique(found.begin(), found.end(), same_triangle), found.end());
  if (found.size() > max_count) {
    overflowed_ = true;
    return;
  }
  for (const auto& [triangle, slot] : found) {
    slots_.push_back(slot);
    boxes_.push_back(triangle_box(&tree.corners_[3 * std::size_t{slot}]));
  }
}

AabbTree::BoundedHit LocalTriangles::nearest_bounded(const Vec3d& p, double accept_sq, double cap_sq) const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(cap_sq >= 0.0)) return {kInfinity, AabbTree::kNoSlot};
  double bound_sq = cap_sq;
  std::uint32_t found = AabbTree::kNoSlot;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const double d_sq =
        distance_sq_within(&tree_->corners_[3 * std::size_t{slots_[i]}], boxes_[i], p, bound_sq);
    if (d_sq > bound_sq) continue;
    bound_sq = d_sq;
    found = slots_[i];
    if (d_sq <= accept_sq) break;
  }
  return found != AabbTree::kNoSlot ? AabbTree::BoundedHit{bound_sq, found}
                                    : AabbTree::BoundedHit{kInfinity, AabbTree::kNoSlot};
}

bool LocalTriangles::one_triangle_near_all(std::span<const Vec3d> points, double r_sq) const {
  if (!(r_sq >= 0.0) || points.empty()) return false;
  for (std::size_t i = 0; i < slots_.size(); ++i)
    if (triangle_near_all(&tree_->corners_[3 * std::size_t{slots_[i]}], boxes_[i], points, r_sq)) return true;
  return false;
}

bool AabbTree::any_within(const Vec3d& p, double r) const {
  if (!(r >= 0.0)) return false;
  const double r_sq = r * r;
  const double d_sq = squared_distance_bounded(p, r_sq, r_sq);
  return d_sq <= r_sq && d_sq != std::numeric_limits<double>::infinity();
}

}  // namespace mr::spatial
