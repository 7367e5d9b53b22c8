#pragma once
// Exact rational points (GMP mpq) for positions constructed by cuts, and the
// predicates of predicates.h evaluated exactly on them.
//
// A double converts to an mpq exactly, so every double point is also an
// ExactPoint3 and mixed double/rational predicates are exact too (see
// hybrid_point.h for the filtered mixed versions used in meshes).

#include <mr/kernel/predicates.h>

#include <gmpxx.h>

namespace mr {

struct ExactPoint3 {
  mpq_class x, y, z;

  ExactPoint3() = default;
  ExactPoint3(mpq_class x_, mpq_class y_, mpq_class z_)
      : x(std::move(x_)), y(std::move(y_)), z(std::move(z_)) {}
  /// Exact: every finite double is a rational. Precondition: p is finite.
  explicit ExactPoint3(const Vec3d& p) : x(p.x()), y(p.y()), z(p.z()) {}

  const mpq_class& operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }
  friend bool operator==(const ExactPoint3& a, const ExactPoint3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  }
};

/// The double nearest to q (ties to even), unlike mpq_class::get_d() which
/// truncates. Precondition: |q| does not exceed the largest finite double.
double round_to_nearest(const mpq_class& q);

/// Coordinates rounded to the nearest doubles.
Vec3d round_to_nearest(const ExactPoint3& p);

/// True when every coordinate of p is exactly a double.
bool is_representable(const ExactPoint3& p);

/// The bits of the largest coordinate (numerator plus denominator): what
/// every exact operation on p costs grows with it.
std::size_t bit_size(const ExactPoint3& p);

/// Exact evaluations, same conventions as predicates.h.
int orient3d(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, const ExactPoint3& d);
int orient2d_projected(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, int axis);
int insphere(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, const ExactPoint3& d,
             const ExactPoint3& e);

}  // namespace mr
