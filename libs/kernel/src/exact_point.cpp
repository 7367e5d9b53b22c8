#include <mr/kernel/exact_point.h>

#include "homogeneous.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mr {
namespace {

bool has_even_mantissa(double d) { return (std::bit_cast<std::uint64_t>(d) & 1u) == 0; }

mpq_class determinant3(const mpq_class& ux, const mpq_class& uy, const mpq_class& uz, const mpq_class& vx,
                       const mpq_class& vy, const mpq_class& vz, const mpq_class& wx, const mpq_class& wy,
                       const mpq_class& wz) {
  return ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
}

}  // namespace

namespace detail {

Homogeneous homogeneous(const ExactPoint3& p) {
  const mpz_class& dx = p.x.get_den();
  const mpz_class& dy = p.y.get_den();
  const mpz_class& dz = p.z.get_den();
  Homogeneous h;
  if (dx == dy && dy == dz) {
    h.w = dx;
  } else {
    mpz_lcm(h.w.get_mpz_t(), dx.get_mpz_t(), dy.get_mpz_t());
    mpz_lcm(h.w.get_mpz_t(), h.w.get_mpz_t(), dz.get_mpz_t());
  }
  const auto scaled = [&](const mpq_class& q) {
    if (q.get_den() == h.w) return mpz_class(q.get_num());
    mpz_class factor;
    mpz_divexact(factor.get_mpz_t(), h.w.get_mpz_t(), q.get_den().get_mpz_t());
    return mpz_class(q.get_num() * factor);
  };
  h.x = scaled(p.x);
  h.y = scaled(p.y);
  h.z = scaled(p.z);
  return h;
}

// q - p, times the positive p.w * q.w.
std::array<mpz_class, 3> scaled_difference(const Homogeneous& q, const Homogeneous& p) {
  return {q.x * p.w - p.x * q.w, q.y * p.w - p.y * q.w, q.z * p.w - p.z * q.w};
}

}  // namespace detail

double round_to_nearest(const mpq_class& q) {
  const double truncated = q.get_d();  // rounds toward zero
  const mpq_class low(truncated);
  if (low == q) return truncated;
  const double away = std::nextafter(truncated, sgn(q) > 0 ? std::numeric_limits<double>::infinity()
                                                           : -std::numeric_limits<double>::infinity());
  const mpq_class midpoint = (low + mpq_class(away)) / 2;
  const int side = cmp(abs(q), abs(midpoint));
  if (side < 0) return truncated;
  if (side > 0) return away;
  return has_even_mantissa(truncated) ? truncated : away;
}

Vec3d round_to_nearest(const ExactPoint3& p) {
  return {round_to_nearest(p.x), round_to_nearest(p.y), round_to_nearest(p.z)};
}

bool is_representable(const ExactPoint3& p) {
  for (int axis = 0; axis < 3; ++axis) {
    const mpq_class& q = p[axis];
    if (q != mpq_class(q.get_d())) return false;
  }
  return true;
}

std::size_t bit_size(const ExactPoint3& p) {
  std::size_t bits = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const mpq_class& q = p[axis];
    bits = std::max(bits, mpz_sizeinbase(q.get_num_mpz_t(), 2) + mpz_sizeinbase(q.get_den_mpz_t(), 2));
  }
  return bits;
}

int orient3d(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, const ExactPoint3& d) {
  const detail::Homogeneous ha = detail::homogeneous(a);
  const auto u = detail::scaled_difference(detail::homogeneous(b), ha);
  const auto v = detail::scaled_difference(detail::homogeneous(c), ha);
  const auto w = detail::scaled_difference(detail::homogeneous(d), ha);
  const mpz_class det = u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
                        u[2] * (v[0] * w[1] - v[1] * w[0]);
  return sgn(det);
}

int orient2d_projected(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, int axis) {
  const int i = axis == 0 ? 1 : 0;
  const int j = axis == 2 ? 1 : 2;
  const detail::Homogeneous ha = detail::homogeneous(a);
  const auto u = detail::scaled_difference(detail::homogeneous(b), ha);
  const auto v = detail::scaled_difference(detail::homogeneous(c), ha);
  const mpz_class det = u[i] * v[j] - u[j] * v[i];
  return sgn(det);
}

int insphere(const ExactPoint3& a, const ExactPoint3& b, const ExactPoint3& c, const ExactPoint3& d,
             const ExactPoint3& e) {
  // Rows (p - e, |p - e|^2) for p = a, b, c, d; expanded along the lift column.
  // That determinant is negative when e is inside and orient3d(a, b, c, d) > 0,
  // hence the final sign flip.
  const ExactPoint3* rows[4] = {&a, &b, &c, &d};
  mpq_class x[4], y[4], z[4], lift[4];
  for (int r = 0; r < 4; ++r) {
    x[r] = rows[r]->x - e.x;
    y[r] = rows[r]->y - e.y;
    z[r] = rows[r]->z - e.z;
    lift[r] = x[r] * x[r] + y[r] * y[r] + z[r] * z[r];
  }
  auto minor = [&](int r0, int r1, int r2) {
    return determinant3(x[r0], y[r0], z[r0], x[r1], y[r1], z[r1], x[r2], y[r2], z[r2]);
  };
  const mpq_class det = -lift[0] * minor(1, 2, 3) + lift[1] * minor(0, 2, 3) - lift[2] * minor(0, 1, 3) +
                        lift[3] * minor(0, 1, 2);
  return -sgn(det);
}

}  // namespace mr
