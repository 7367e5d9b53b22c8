#pragma once
// The hybrid vertex position of the paper's section 3.4: a double position,
// plus an exact rational one kept only while rounding to the doubles would
// invert an incident tet. Rationals thus stay short-lived: they are dropped as
// soon as try_round (rounding.h) accepts, so most vertices of a mesh cost
// plain doubles and plain filtered predicates.
//
// Invariant: when `exact` is present, `approx` is its coordinate-wise nearest
// double. Create rational points with from_exact only: the predicates below
// rely on the invariant (their interval filter encloses the rational between
// the neighbours of approx).

#include <mr/kernel/exact_point.h>

#include <memory>

namespace mr {

/// An optional ExactPoint3 kept on the heap, copied deeply: 8 bytes where
/// std::optional<ExactPoint3> takes 104, for positions that are doubles
/// almost always (a tet mesh's vertex array was 128 bytes a vertex).
class OptionalExactPoint {
 public:
  OptionalExactPoint() = default;
  OptionalExactPoint(const OptionalExactPoint& other)
      : point_(other.point_ ? std::make_unique<ExactPoint3>(*other.point_) : nullptr) {}
  OptionalExactPoint(OptionalExactPoint&&) noexcept = default;
  OptionalExactPoint& operator=(const OptionalExactPoint& other) {
    if (this != &other) point_ = other.point_ ? std::make_unique<ExactPoint3>(*other.point_) : nullptr;
    return *this;
  }
  OptionalExactPoint& operator=(OptionalExactPoint&&) noexcept = default;
  OptionalExactPoint& operator=(ExactPoint3 point) {
    point_ = std::make_unique<ExactPoint3>(std::move(point));
    return *this;
  }

  bool has_value() const { return point_ != nullptr; }
  explicit operator bool() const { return has_value(); }
  const ExactPoint3& operator*() const { return *point_; }
  const ExactPoint3* operator->() const { return point_.get(); }
  void reset() { point_.reset(); }

 private:
  std::unique_ptr<ExactPoint3> point_;
};

struct HybridPoint {
  Vec3d approx = Vec3d::Zero();
  OptionalExactPoint exact;

  HybridPoint() = default;
  /// A plain double position (implicit: a double point is a hybrid point).
  HybridPoint(const Vec3d& p) : approx(p) {}  // NOLINT(google-explicit-constructor)

  /// Keeps the rational only when it is not exactly a double.
  static HybridPoint from_exact(ExactPoint3 p);

  bool is_exact() const { return exact.has_value(); }
  /// The exact position, whichever representation holds it.
  ExactPoint3 to_exact() const { return exact ? *exact : ExactPoint3(approx); }

  /// Geometric equality of the represented positions (exact comparison).
  friend bool operator==(const HybridPoint& a, const HybridPoint& b);
};

/// Exact predicates on hybrid points; same conventions as predicates.h. When
/// all points are doubles this is the filtered double predicate; otherwise an
/// interval filter on the rationals runs first and GMP decides only the
/// ambiguous cases.
int orient3d(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c, const HybridPoint& d);
int orient2d_projected(const HybridPoint& a, const HybridPoint& b, const HybridPoint& c, int axis);

}  // namespace mr
