// Why the sampled test is conservative.
//
// Lemma (covering radius of a triangle by its own vertices). Let T be a
// triangle, possibly degenerate, with longest edge L. Every point x of T is
// within L/sqrt(3) of one of its vertices.
//   If x is a vertex there is nothing to show. If T is degenerate (collinear
//   corners), x lies between two corners u, v that are consecutive on the
//   line; |uv| <= L, so min(|xu|, |xv|) <= L/2 < L/sqrt(3). Otherwise the
//   three edges are seen from x under angles that sum to 2*pi (x interior),
//   or one of them is seen under the angle pi (x on that edge); either way
//   some edge uv is seen under an angle theta >= 2*pi/3. With a = |xu| and
//   b = |xv|, the law of cosines gives
//     |uv|^2 = a^2 + b^2 - 2ab cos(theta) >= a^2 + b^2 + ab >= 3 min(a, b)^2,
//   so min(a, b) <= |uv|/sqrt(3) <= L/sqrt(3).
// For a segment of length L the same radius is L/2.
//
// Theorem. f(x) = distance from x to the input is 1-Lipschitz. Cut the query
// triangle T into pieces T_i (longest edge L_i) whose vertices are the
// samples. If every vertex v of every piece has f(v) <= eps - L_i/sqrt(3),
// then every x of T lies in some T_i, within L_i/sqrt(3) of a vertex v of
// that piece, and f(x) <= f(v) + |x - v| <= eps. So "inside" is never wrong.
//
// The covering radius r(d) = L_i/sqrt(3) <= d/sqrt(3) when pieces have edges
// <= d: this is the paper's d_err = d/sqrt(3), eps_hat = eps - d_err. For the
// paper's regular triangular lattice of spacing d it is exactly the
// circumradius d/sqrt(3) of the lattice's equilateral cells; the Lattice
// pattern below cuts T into n^2 copies similar to T (n = ceil(L/d)), which
// is that lattice for an equilateral T and gives the same bound for any T
// without the paper's extra edge samples. The Adaptive pattern cuts T by
// longest-edge bisection (longest edges never grow from parent to child)
// and checks each piece with its own, usually larger, eps - L_i/sqrt(3).
//
// Shortcut. The distance to one convex input triangle is a convex function,
// so if every corner of a query element is within limit of the same input
// triangle, so is the whole element: no sampling needed. This decides most
// elements lying on the input (tracked faces, their sub-triangles) at once.
//
// Rounding: sample positions and distances are computed in doubles. Every
// threshold uses limit = eps - margin, where margin (1e-9 of the input's
// size plus 64 ulps of its largest coordinate) dominates those errors.

#include "sampled_envelope.h"

#include <mr/core/errors.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

namespace mr::envelope {

namespace {

constexpr double kInvSqrt3 = 0.57735026918962576451;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Beyond this many steps along its longest edge, a triangle is checked by
// bisection instead of the lattice: a lattice costs n^2 samples, while
// bisection stops wherever a piece lies near one input triangle, so its cost
// follows the input edges the triangle spans (large flat CAD faces).
constexpr double kLargestLattice = 16.0;

void check_options(const EnvelopeOptions& options) {
  if (!(options.epsilon > 0.0) || !std::isfinite(options.epsilon)) {
    throw UsageError("envelope: epsilon must be positive and finite");
  }
  if (!(options.sampling_step >= 0.0) || !std::isfinite(options.sampling_step)) {
    throw UsageError("envelope: sampling step must be non-negative and finite (0: epsilon)");
  }
  if (options.stage < 1) throw UsageError("envelope: stage must be at least 1");
}

double rounding_margin(const spatial::AabbTree& tree, double epsilon) {
  if (tree.empty()) return 1e-9 * epsilon;
  const spatial::AabbBox box = tree.bounds();
  const double diagonal = (box.hi - box.lo).norm();
  const double largest = std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff());
  return 1e-9 * (diagonal + epsilon) + 64.0 * DBL_EPSILON * largest;
}

bool all_finite(std::initializer_list<const Vec3d*> points) {
  return std::all_of(points.begin(), points.end(), [](const Vec3d* p) { return p->allFinite(); });
}

// Index i of the longest edge (v[i], v[(i + 1) % 3]) and its length.
std::pair<int, double> longest_edge(const std::array<Vec3d, 3>& v) {
  int longest = 0;
  double length_sq = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double l = (v[(i + 1) % 3] - v[i]).squaredNorm();
    if (l > length_sq) {
      length_sq = l;
      longest = i;
    }
  }
  return {longest, std::sqrt(length_sq)};
}

double longest_edge_length(const std::array<Vec3d, 3>& v) { return longest_edge(v).second; }

// At most this many input triangles near an element are searched one by one.
constexpr std::size_t kMostNearby = 48;
// Lattices of fewer steps a side search the tree for each point.
constexpr double kSmallestListedLattice = 4.0;

}  // namespace

// Where one test searches the input: the whole tree, or, when few input
// triangles come within reach of the element under test, those triangles
// one by one (spatial::LocalTriangles). Every sample lies in the element,
// so both give the same answers; the short list spares a descent from the
// root for each sample and for each one-triangle search of a bisection
// (trimesh/teapot: 58 samples and as many one-triangle searches per face
// bisected, 1% of those successful; tetrahedralize 7.0 -> 5.1 s user, the
// same output).
class SampledEnvelope::Nearby {
 public:
  explicit Nearby(const spatial::AabbTree& tree) : tree_(tree) {}
  /// The triangles within `reach` of the box of `element`, if few.
  Nearby(const spatial::AabbTree& tree, std::initializer_list<Vec3d> element, double reach) : tree_(tree) {
    Vec3d lo = *element.begin(), hi = lo;
    for (const Vec3d& p : element) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    // Samples are computed in doubles: a few ulps outside the box.
    const double slack =
        1e-6 * reach + 16.0 * DBL_EPSILON * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    const Vec3d grow = Vec3d::Constant(reach + slack);
    local_.emplace(tree, lo - grow, hi + grow, kMostNearby);
    if (local_->overflowed()) local_.reset();
  }

  Sample nearest(const Vec3d& p, double accept_sq, double cap_sq) const {
    return local_ ? local_->nearest_bounded(p, accept_sq, cap_sq)
                  : tree_.nearest_bounded(p, accept_sq, cap_sq);
  }
  bool one_near_all(std::span<const Vec3d> points, double r_sq) const {
    return local_ ? local_->one_triangle_near_all(points, r_sq) : tree_.one_triangle_near_all(points, r_sq);
  }

 private:
  const spatial::AabbTree& tree_;
  std::optional<spatial::LocalTriangles> local_;
};

SampledEnvelope::SampledEnvelope(const TriangleSoup& input, const EnvelopeOptions& options) {
  check_options(options);
  // Envelope queries are distances near the input: a soup's triangles span
  // the model, and without pieces every sample visited most of them.
  tree_ = spatial::AabbTree(input, {.cut_large_triangles = true});
  epsilon_ = options.epsilon;
  const double d = options.sampling_step > 0.0 ? options.sampling_step : options.epsilon;
  step_ = d / options.stage;
  limit_ = epsilon_ - rounding_margin(tree_, epsilon_);
  for (const Triangle& t : input.triangles) {
    largest_triangle_ =
        std::max(largest_triangle_,
                 longest_edge_length({input.positions[t[0]], input.positions[t[1]], input.positions[t[2]]}));
  }
  pattern_ = options.pattern;
}

SampledEnvelope::Sample SampledEnvelope::sample(const Nearby& nearby, const Vec3d& p, double accept) const {
  // A point on an input triangle is at 0, the least any search can find: a
  // search stops there even when no smaller radius would let it stop sooner.
  const double accept_sq = accept > 0.0 ? accept * accept : 0.0;
  const Sample hit = nearby.nearest(p, accept_sq, limit_ * limit_);
  if (hit.squared_distance <= limit_ * limit_) return hit;
  return {kInfinity, spatial::AabbTree::kNoSlot};
}

bool SampledEnvelope::accepts(double squared_distance, double covering_radius) const {
  const double threshold = limit_ - covering_radius;
  return threshold >= 0.0 && squared_distance <= threshold * threshold;
}

bool SampledEnvelope::is_inside(const Vec3d& p) const {
  return p.allFinite() && sample(Nearby(tree_), p, limit_).squared_distance != kInfinity;
}

bool SampledEnvelope::is_inside(const Vec3d& a, const Vec3d& b) const {
  if (!all_finite({&a, &b})) return false;
  if (pattern_ == SamplingPattern::Lattice) return lattice_segment(a, b);
  if (near_one_input_triangle(Nearby(tree_), {a, b})) return true;
  const Nearby nearby(tree_, {a, b}, limit_);
  const double accept = limit_ - 0.5 * (b - a).norm();
  const Sample da = sample(nearby, a, accept);
  if (da.squared_distance == kInfinity) return false;
  const Sample db = sample(nearby, b, accept);
  if (db.squared_distance == kInfinity) return false;
  return adaptive_segment(nearby, a, b, da, db);
}

bool SampledEnvelope::is_inside(const Vec3d& a, const Vec3d& b, const Vec3d& c) const {
  if (!all_finite({&a, &b, &c})) return false;
  if (pattern_ == SamplingPattern::Lattice) return lattice_triangle(a, b, c);
  if (near_one_input_triangle(Nearby(tree_), {a, b, c})) return true;
  return adaptive_from_corners(Nearby(tree_, {a, b, c}, limit_), {a, b, c});
}

bool SampledEnvelope::adaptive_from_corners(const Nearby& nearby, const std::array<Vec3d, 3>& v) const {
  const double accept = limit_ - longest_edge_length(v) * kInvSqrt3;
  std::array<Sample, 3> d{};
  for (int i = 0; i < 3; ++i) {
    d[i] = sample(nearby, v[i], accept);
    if (d[i].squared_distance == kInfinity) return false;
  }
  return adaptive_triangle(nearby, v, d);
}

// da, db: squared-distance bounds of the ends (see sample()).
bool SampledEnvelope::adaptive_segment(const Nearby& nearby, const Vec3d& a, const Vec3d& b, Sample da,
                                       Sample db) const {
  const double length = (b - a).norm();
  if (accepts(std::max(da.squared_distance, db.squared_distance), 0.5 * length)) return true;
  if (length <= step_) return false;
  if (near_a_sampled_triangle<2>({a, b}, {da, db}) || near_one_input_triangle(nearby, {a, b})) return true;
  const Vec3d m = 0.5 * (a + b);
  const Sample dm = sample(nearby, m, limit_ - 0.25 * length);
  if (dm.squared_distance == kInfinity) return false;
  return adaptive_segment(nearby, a, m, da, dm) && adaptive_segment(nearby, m, b, dm, db);
}

// Splits the longest edge at its midpoint m. The midpoint is sampled with
// the smaller acceptance radius of the two halves, so its early-exit bound
// is good enough for both halves and for all their descendants (whose
// longest edges, hence radii eps - L/sqrt(3), only grow).
bool SampledEnvelope::adaptive_triangle(const Nearby& nearby, const std::array<Vec3d, 3>& v,
                                        const std::array<Sample, 3>& d) const {
  const auto [i, length] = longest_edge(v);
  const double farthest = std::max({d[0].squared_distance, d[1].squared_distance, d[2].squared_distance});
  if (accepts(farthest, length * kInvSqrt3)) return true;
  if (length <= step_) return false;
  if (near_a_sampled_triangle(v, d) || near_one_input_triangle(nearby, {v[0], v[1], v[2]})) return true;
  const int j = (i + 1) % 3;
  const int k = (i + 2) % 3;
  const std::array<Vec3d, 3> first{v[i], 0.5 * (v[i] + v[j]), v[k]};
  const std::array<Vec3d, 3> second{first[1], v[j], v[k]};
  const double child_length = std::max(longest_edge_length(first), longest_edge_length(second));
  const Sample dm = sample(nearby, first[1], limit_ - child_length * kInvSqrt3);
  if (dm.squared_distance == kInfinity) return false;
  return adaptive_triangle(nearby, first, {d[i], dm, d[k]}) &&
         adaptive_triangle(nearby, second, {dm, d[j], d[k]});
}

bool SampledEnvelope::near_one_input_triangle(const Nearby& nearby,
                                              std::initializer_list<Vec3d> corners) const {
  // Points within limit of one triangle are at most its longest edge plus
  // twice the limit apart: a wider set needs no search.
  const double reach = largest_triangle_ + 2.0 * limit_;
  for (auto p = corners.begin(); p != corners.end(); ++p) {
    for (auto q = p + 1; q != corners.end(); ++q) {
      if ((*p - *q).squaredNorm() > reach * reach) return false;
    }
  }
  return nearby.one_near_all(std::span(corners.begin(), corners.size()), limit_ * limit_);
}

template <std::size_t N>
bool SampledEnvelope::near_a_sampled_triangle(const std::array<Vec3d, N>& corners,
                                              const std::array<Sample, N>& samples) const {
  for (std::size_t i = 0; i < N; ++i) {
    const std::uint32_t slot = samples[i].slot;
    bool tried = slot == spatial::AabbTree::kNoSlot;
    for (std::size_t j = 0; j < i && !tried; ++j) tried = samples[j].slot == slot;
    if (!tried && tree_.slot_near_all(slot, corners, limit_ * limit_)) return true;
  }
  return false;
}

bool SampledEnvelope::lattice_segment(const Vec3d& a, const Vec3d& b) const {
  if (near_one_input_triangle(Nearby(tree_), {a, b})) return true;
  const double length = (b - a).norm();
  const double n = std::max(1.0, std::ceil(length / step_));
  const double threshold = limit_ - 0.5 * length / n;
  if (threshold < 0.0) return false;
  const double threshold_sq = threshold * threshold;
  for (double i = 0; i <= n; ++i) {
    const Vec3d p = a + (i / n) * (b - a);
    if (tree_.squared_distance_bounded(p, threshold_sq, threshold_sq) > threshold_sq) return false;
  }
  return true;
}

// Lattice vertices a + (i/n)(b - a) + (j/n)(c - a), i + j <= n: the vertices
// of the n^2 copies of T scaled by 1/n.
bool SampledEnvelope::lattice_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c) const {
  const double length = longest_edge_length({a, b, c});
  const double n = std::max(1.0, std::ceil(length / step_));
  if (n > kLargestLattice) {
    return near_one_input_triangle(Nearby(tree_), {a, b, c}) ||
           adaptive_from_corners(Nearby(tree_, {a, b, c}, limit_), {a, b, c});
  }
  const double threshold = limit_ - length / n * kInvSqrt3;
  if (threshold < 0.0) return false;
  const double threshold_sq = threshold * threshold;

  // The whole triangle as one piece (n = 1) first: small triangles close to
  // the input need no lattice at all.
  // A triangle too long to be taken whole only needs its corners within the
  // threshold, and a search may stop at the first input triangle that near
  // (else it looks for the nearest, which on long faces over fine input
  // was most of the simplifier's envelope time).
  const double whole = limit_ - length * kInvSqrt3;
  double worst_corner_sq = 0.0;
  for (const Vec3d* corner : {&a, &b, &c}) {
    const double d_sq = sample(Nearby(tree_), *corner, whole >= 0.0 ? whole : threshold).squared_distance;
    if (d_sq > threshold_sq) return false;
    worst_corner_sq = std::max(worst_corner_sq, d_sq);
  }
  if (accepts(worst_corner_sq, length * kInvSqrt3)) return true;
  if (near_one_input_triangle(Nearby(tree_), {a, b, c})) return true;
  // A few lattice points cost less than listing the triangles near them.
  const Nearby nearby = n >= kSmallestListedLattice ? Nearby(tree_, {a, b, c}, threshold) : Nearby(tree_);
  const auto inside = [&](const Vec3d& p) {
    return nearby.nearest(p, threshold_sq, threshold_sq).squared_distance <= threshold_sq;
  };
  const Vec3d ab = b - a;
  const Vec3d ac = c - a;
  for (double i = 0; i <= n; ++i) {
    for (double j = 0; i + j <= n; ++j) {
      if (!inside(a + (i / n) * ab + (j / n) * ac)) return false;
    }
  }
  return true;
}

}  // namespace mr::envelope
