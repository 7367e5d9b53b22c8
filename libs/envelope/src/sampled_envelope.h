#pragma once
// The sampled envelope test of the paper (section 3.4), made provably
// conservative. See sampled_envelope.cpp for the covering-radius argument.

#include <mr/envelope/envelope.h>
#include <mr/spatial/aabb_tree.h>

#include <initializer_list>

namespace mr::envelope {

class SampledEnvelope final : public Envelope {
 public:
  SampledEnvelope(const TriangleSoup& input, const EnvelopeOptions& options);

  bool is_inside(const Vec3d& p) const override;
  bool is_inside(const Vec3d& a, const Vec3d& b) const override;
  bool is_inside(const Vec3d& a, const Vec3d& b, const Vec3d& c) const override;
  double epsilon() const override { return epsilon_; }

 private:
  // Upper bound of the squared distance from p to the input, exact when it
  // lies in (accept^2, limit^2], infinity beyond limit (see the tree), and
  // the input triangle that gave it.
  using Sample = spatial::AabbTree::BoundedHit;
  class Nearby;
  Sample sample(const Nearby& nearby, const Vec3d& p, double accept) const;
  bool accepts(double squared_distance, double covering_radius) const;
  // Whether the corners (hence their hull) are all within limit of one input triangle.
  bool near_one_input_triangle(const Nearby& nearby, std::initializer_list<Vec3d> corners) const;
  // The same, trying only the triangles that gave the corners' samples: a
  // few distances instead of a search (for the pieces of a bisection).
  template <std::size_t N>
  bool near_a_sampled_triangle(const std::array<Vec3d, N>& corners,
                               const std::array<Sample, N>& samples) const;

  bool adaptive_segment(const Nearby& nearby, const Vec3d& a, const Vec3d& b, Sample da, Sample db) const;
  bool adaptive_triangle(const Nearby& nearby, const std::array<Vec3d, 3>& v,
                         const std::array<Sample, 3>& d) const;
  bool adaptive_from_corners(const Nearby& nearby, const std::array<Vec3d, 3>& v) const;
  bool lattice_segment(const Vec3d& a, const Vec3d& b) const;
  bool lattice_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c) const;

  spatial::AabbTree tree_;
  double epsilon_ = 0.0;
  double step_ = 0.0;              // d_k = d / k
  double limit_ = 0.0;             // epsilon minus the rounding margin
  double largest_triangle_ = 0.0;  // longest edge of all input triangles
  SamplingPattern pattern_ = SamplingPattern::Lattice;
};

}  // namespace mr::envelope
