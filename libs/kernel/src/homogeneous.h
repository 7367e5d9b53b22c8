#pragma once
// Rational points as integers over one common denominator, for the exact
// predicates and constructions of the kernel (not part of its interface).

#include <mr/kernel/exact_point.h>

#include <array>

namespace mr::detail {

// A point as integers (x, y, z) / w with w > 0. Every mpq operation reduces
// its result by a gcd, which on the long numbers of nested cut points cost
// most of the insertion time; integer products need no reduction, and signs
// are kept since every denominator is positive.
struct Homogeneous {
  mpz_class x, y, z, w;
};

Homogeneous homogeneous(const ExactPoint3& p);

/// q - p, times the positive p.w * q.w.
std::array<mpz_class, 3> scaled_difference(const Homogeneous& q, const Homogeneous& p);

}  // namespace mr::detail
