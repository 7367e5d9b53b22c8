#pragma once
// Containment in the epsilon-envelope of a triangle soup: the set of points
// within distance epsilon of some input triangle. One interface, so that the
// sampled test of the paper (section 3.4) and an exact polyhedral envelope
// (Wang et al. 2020) can sit behind the same calls and be compared.
//
// Every implementation is conservative: it may answer "outside" for an
// element that is inside, but answers "inside" only when every point of the
// element is within epsilon of the input (up to a relative rounding margin
// of about 1e-9 of the input's size).

#include <mr/core/triangle_soup.h>
#include <mr/core/types.h>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace mr::envelope {

enum class EnvelopeKind {
  Sampled,  ///< samples checked against an AABB tree of the input (the paper)
};

/// How the sampled envelope places its samples on a triangle.
enum class SamplingPattern {
  /// The paper's lattice: the triangle cut into n^2 copies similar to it with
  /// edges no longer than the sampling step, every lattice vertex a sample.
  /// The default: fastest on triangles of ordinary shape (see bench/spatial_bench).
  /// Triangles more than 16 steps long are checked as with Adaptive.
  Lattice,
  /// Longest-edge bisection, stopping early wherever the samples found so far
  /// prove a piece inside; rejects only pieces whose edges are all no longer
  /// than the sampling step. Cost grows with the length, not the area, of
  /// long thin triangles, where the lattice is quadratic; and a piece whose
  /// corners all lie near one input triangle is accepted at once (the
  /// distance to a triangle is convex), so large faces over a flat input
  /// cost about the length of the input edges they span.
  Adaptive,
};

struct EnvelopeOptions {
  EnvelopeKind kind = EnvelopeKind::Sampled;
  /// Envelope radius, absolute (callers turn a relative epsilon into this). > 0.
  double epsilon = 0.0;
  /// Sampling step d; 0 means d = epsilon, the paper's choice. The
  /// conservative radius is then eps_hat = eps - d_k/sqrt(3) at worst.
  double sampling_step = 0.0;
  /// Stage k >= 1 of the paper's staged refinement: the step becomes d/k,
  /// which enlarges the conservative envelope towards epsilon.
  int stage = 1;
  SamplingPattern pattern = SamplingPattern::Lattice;
};

using TriangleCorners = std::array<Vec3d, 3>;

class Envelope {
 public:
  virtual ~Envelope() = default;

  virtual bool is_inside(const Vec3d& p) const = 0;
  virtual bool is_inside(const Vec3d& a, const Vec3d& b) const = 0;
  virtual bool is_inside(const Vec3d& a, const Vec3d& b, const Vec3d& c) const = 0;

  /// is_inside for every triangle, in parallel (TBB); answer i (1 inside,
  /// 0 outside) belongs to triangle i, whatever the thread count.
  std::vector<std::uint8_t> are_inside(std::span<const TriangleCorners> triangles) const;
  /// The same for the triangles of a soup.
  std::vector<std::uint8_t> are_inside(const TriangleSoup& soup) const;

  virtual double epsilon() const = 0;
};

/// Builds the envelope of `input` (kept by copy: `input` may go away).
/// Throws mr::UsageError on a non-positive or non-finite epsilon or sampling
/// step, a stage below 1, or an inconsistent soup.
std::unique_ptr<Envelope> make_envelope(const TriangleSoup& input, const EnvelopeOptions& options);

}  // namespace mr::envelope
