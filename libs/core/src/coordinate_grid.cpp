#include <mr/core/coordinate_grid.h>

#include <mr/core/errors.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace mr {
namespace {

// Steps of margin a quantized grid keeps around the box it is made for.
constexpr int kQuantizationMargin = 8;

// Largest |k| of a float32_about grid: k * unit is a float exactly.
constexpr std::int64_t kAboutLevels = (std::int64_t{1} << 24) - 1;

double nearest_float(double x) {
  const float f = static_cast<float>(x);  // round to nearest, ties to even
  return static_cast<double>(f);
}

double float_steps(double g, int steps) {
  float f = static_cast<float>(g);
  const float towards =
      steps > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
  for (int k = 0; k < std::abs(steps); ++k) f = std::nextafter(f, towards);
  return static_cast<double>(f);
}

// Draco's encoder options hold numbers as text (std::to_string: six
// decimals), so an explicit origin or range reaches the quantizer as the
// float nearest to its six-decimal rendering. This is that float: the
// value the file stores and the decoder uses.
float through_draco_options(float x) {
  for (int k = 0; k < 4; ++k) {
    const float y = std::strtof(std::to_string(x).c_str(), nullptr);
    if (y == x) break;
    x = y;
  }
  return x;
}

// Draco's options cannot tell apart values closer than this (or a float step).
float options_resolution(double x) {
  const float f = static_cast<float>(x);
  return std::max(1e-6f, std::nextafter(std::abs(f), std::numeric_limits<float>::infinity()) - std::abs(f));
}

double double_steps(double g, int steps) {
  const double towards =
      steps > 0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  for (int k = 0; k < std::abs(steps); ++k) g = std::nextafter(g, towards);
  return g;
}

}  // namespace

CoordinateGrid::CoordinateGrid(Kind kind, const Quantization& quantization)
    : kind_(kind), quantization_(quantization) {
  if (kind_ != Kind::quantized) return;
  if (quantization_.bits < 1 || quantization_.bits > 30)
    throw UsageError("quantization must be 1 to 30 bits, not " + std::to_string(quantization_.bits));
  if (!(quantization_.range > 0.0f) || !std::isfinite(quantization_.range))
    throw UsageError("quantization range must be finite and > 0");
  for (float& o : quantization_.origin) o = through_draco_options(o);
  quantization_.range = through_draco_options(quantization_.range);
  if (!(quantization_.range > 0.0f)) throw UsageError("quantization range must be at least 1e-6");
  max_level_ = (std::int64_t{1} << quantization_.bits) - 1;
  // As Draco's Dequantizer::Init: the division in float.
  delta_ = quantization_.range / static_cast<float>(max_level_);
  // As Draco's Quantizer::Init.
  inverse_delta_ = static_cast<float>(max_level_) / quantization_.range;
}

CoordinateGrid CoordinateGrid::quantized(const Quantization& quantization) {
  return CoordinateGrid(Kind::quantized, quantization);
}

CoordinateGrid CoordinateGrid::float32_about(const Vec3d& origin, double unit) {
  int exponent = 0;
  if (!(unit > 0) || !std::isfinite(unit) || std::frexp(unit, &exponent) != 0.5)
    throw UsageError("the unit of a float32 grid about an origin must be a power of two");
  for (int axis = 0; axis < 3; ++axis) {
    const double steps = origin[axis] / unit;
    if (!std::isfinite(steps) || std::abs(steps) >= 0x1p52 || steps != std::round(steps))
      throw UsageError("the origin of a float32 grid must be a multiple of its unit, below 2^52 units");
  }
  CoordinateGrid grid(Kind::float32_about, {});
  grid.origin_ = origin;
  grid.unit_ = unit;
  return grid;
}

CoordinateGrid CoordinateGrid::float32_over(const Vec3d& lo, const Vec3d& hi) {
  const CoordinateGrid floats = float32();
  // Floats about the centre cover twice the box's larger half-extent
  // (2^24 units reach 2^(e + 1) for a half-extent below 2^e).
  const double half = 0.5 * (hi - lo).maxCoeff();
  if (!(half > 0) || !std::isfinite(half)) return floats;
  // The unit is also at least twice the double step at the centre, so
  // that the centre is a multiple of it below 2^52 units.
  const Vec3d centre = 0.5 * (lo + hi);
  int half_exponent = 0, centre_exponent = 0;
  std::frexp(half, &half_exponent);  // half < 2^half_exponent
  std::frexp(centre.cwiseAbs().maxCoeff(), &centre_exponent);
  const double unit = std::ldexp(1.0, std::max(half_exponent - 23, centre_exponent - 51));
  if (!(unit > 0) || !std::isfinite(unit)) return floats;
  Vec3d origin;
  for (int axis = 0; axis < 3; ++axis) {
    const double steps = std::round(centre[axis] / unit);
    if (!(std::abs(steps) < 0x1p52)) return floats;
    origin[axis] = steps * unit;
  }
  if (floats.spacing_over(lo, hi) <= 4 * unit) return floats;
  return float32_about(origin, unit);
}

CoordinateGrid CoordinateGrid::quantized_over(const Vec3d& lo, const Vec3d& hi, int bits) {
  if (bits < 1 || bits > 30)
    throw UsageError("quantization must be 1 to 30 bits, not " + std::to_string(bits));
  const double extent = std::max((hi - lo).maxCoeff(), double(std::numeric_limits<float>::min()));
  const double levels = static_cast<double>((std::int64_t{1} << bits) - 1);
  // The margin takes steps of the grid it widens: extent + 2 m (extent + 2 m) / levels = range.
  const double margin_share = 2.0 * kQuantizationMargin / levels;
  const double range = extent / std::max(1.0 - margin_share, 0.5);
  const double margin = 0.5 * (range - extent);
  // Each value moved past what Draco's options can tell apart, so that it
  // still covers the box after going through them.
  Quantization q;
  q.bits = bits;
  double reach = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double origin = lo[axis] - margin;
    q.origin[axis] = through_draco_options(static_cast<float>(origin - 2.0 * options_resolution(origin)));
    reach = std::max(reach, hi[axis] + margin - double(q.origin[axis]));
  }
  q.range = through_draco_options(static_cast<float>(reach + 2.0 * options_resolution(reach)));
  return quantized(q);
}

std::string CoordinateGrid::name() const {
  switch (kind_) {
    case Kind::doubles:
      return "float64";
    case Kind::float32:
      return "float32";
    case Kind::float32_about:
      return "float32 (about a glTF node translation)";
    case Kind::quantized:
      return std::to_string(quantization_.bits) + "-bit quantization";
  }
  return "";
}

double CoordinateGrid::dequantize(int axis, std::int64_t q) const {
  // As Draco's decoder: float(q) * delta, then + origin, each in float.
  const float scaled = static_cast<float>(q) * delta_;
  const float value = scaled + quantization_.origin[static_cast<std::size_t>(axis)];
  return static_cast<double>(value);
}

// The level Draco's encoder stores the float nearest to x at: as its
// AttributeQuantizationTransform, the difference to the origin and the
// scaling each in float.
std::int64_t CoordinateGrid::encoded_level(int axis, double x) const {
  const float value = static_cast<float>(x) - quantization_.origin[static_cast<std::size_t>(axis)];
  return static_cast<std::int64_t>(std::floor(value * inverse_delta_ + 0.5f));
}

// Whether a file on this grid gives x back: x is a float the encoder stores
// at a level that the decoder turns into x again.
bool CoordinateGrid::stored_as_is(int axis, double x) const {
  if (static_cast<double>(static_cast<float>(x)) != x) return false;
  const std::int64_t q = encoded_level(axis, x);
  return q >= 0 && q <= max_level_ && dequantize(axis, q) == x;
}

// The level whose value is nearest to x, among those a file stores as they
// are if any is near.
std::int64_t CoordinateGrid::nearest_level(int axis, double x) const {
  const double origin = quantization_.origin[static_cast<std::size_t>(axis)];
  const double guess = std::round((x - origin) / static_cast<double>(delta_));
  const std::int64_t centre = static_cast<std::int64_t>(std::clamp(guess, 0.0, double(max_level_)));
  // The float arithmetic can put the nearest value a level off the guess.
  std::int64_t best = centre;
  double best_distance = std::abs(dequantize(axis, centre) - x);
  bool best_stored = stored_as_is(axis, dequantize(axis, centre));
  for (std::int64_t q = std::max<std::int64_t>(centre - 2, 0); q <= std::min(centre + 2, max_level_); ++q) {
    if (q == centre) continue;
    const double value = dequantize(axis, q);
    const double distance = std::abs(value - x);
    const bool stored = stored_as_is(axis, value);
    if ((stored && !best_stored) || (stored == best_stored && distance < best_distance)) {
      best = q;
      best_distance = distance;
      best_stored = stored;
    }
  }
  return best;
}

double CoordinateGrid::about_value(int axis, std::int64_t k) const {
  return origin_[axis] + static_cast<double>(k) * unit_;  // exact: see float32_about
}

std::int64_t CoordinateGrid::about_level(int axis, double x) const {
  const double k = std::round((x - origin_[axis]) / unit_);
  if (std::isnan(k)) return 0;
  return static_cast<std::int64_t>(std::clamp(k, -double(kAboutLevels), double(kAboutLevels)));
}

bool CoordinateGrid::holds(const Vec3d& p) const {
  if (nearest(p) != p) return false;
  if (kind_ != Kind::quantized) return true;
  for (int axis = 0; axis < 3; ++axis)
    if (!stored_as_is(axis, p[axis])) return false;
  return true;
}

double CoordinateGrid::nearest(int axis, double x) const {
  switch (kind_) {
    case Kind::doubles:
      return x;
    case Kind::float32:
      return nearest_float(x);
    case Kind::float32_about:
      return about_value(axis, about_level(axis, x));
    case Kind::quantized:
      return dequantize(axis, nearest_level(axis, x));
  }
  return x;
}

// One axis at a time: GCC 12.2 at -O3 vectorizes the three calls of the
// braced form {nearest(0, x), nearest(1, y), nearest(2, z)} and drops the
// float32 rounding of x and y (the SLP vectorizer; -fno-tree-slp-vectorize
// and -O2 are correct). The test "float32 grid" catches it.
Vec3d CoordinateGrid::nearest(const Vec3d& p) const {
  Vec3d out;
  for (int axis = 0; axis < 3; ++axis) out[axis] = nearest(axis, p[axis]);
  return out;
}

double CoordinateGrid::step(int axis, double g, int steps) const {
  switch (kind_) {
    case Kind::doubles:
      return double_steps(g, steps);
    case Kind::float32:
      return float_steps(g, steps);
    case Kind::float32_about:
      return about_value(axis, std::clamp(about_level(axis, g) + steps, -kAboutLevels, kAboutLevels));
    case Kind::quantized: {
      const std::int64_t q = std::clamp(nearest_level(axis, g) + steps, std::int64_t{0}, max_level_);
      return dequantize(axis, q);
    }
  }
  return g;
}

double CoordinateGrid::spacing_over(const Vec3d& lo, const Vec3d& hi) const {
  double spacing = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double x : {lo[axis], hi[axis]}) {
      const double g = nearest(axis, x);
      spacing = std::max({spacing, step(axis, g, 1) - g, g - step(axis, g, -1)});
      // Draco's decoder adds in float: far from the origin, levels finer
      // than a float step there land on the same float.
      if (kind_ == Kind::quantized) spacing = std::max(spacing, float_steps(g, 1) - g);
    }
  }
  return spacing;
}

}  // namespace mr
