#pragma once
// The coordinates a file format can store. A surface that is watertight in
// doubles can intersect itself once its positions are rounded to float32
// (STL, GLB) or to Draco's quantization grid, and users only ever see the
// rounded file; the repair's last stage therefore moves every vertex onto
// the grid its output format stores (mr/repair/round_to_grid.h).
//
// A grid is a product of three sorted sets of doubles, one per axis:
//   - doubles: every double (OBJ, OFF, PLY as written here): rounding is
//     the identity;
//   - float32: every float, rounding to nearest, ties to even;
//   - float32 about an origin (glTF: floats plus the node's translation,
//     in double): origin + k * unit for |k| < 2^24, unit a power of two,
//     origin a multiple of it, so that each k * unit is a float and each
//     sum a double, exactly. Far from the origin, float32 steps grow with
//     the coordinates (0.0078 at 1e5); about the model's centre they
//     stay a 2^-23 share of its size;
//   - quantized: Draco's dequantized values origin[axis] + q * delta,
//     q = 0 .. 2^bits - 1, computed in float arithmetic exactly as Draco's
//     decoder does (delta = range / (2^bits - 1) in float), so that the
//     grid values are the values a reader of the file gets back. Draco
//     takes an explicit origin and range through its text options (six
//     decimals), so both are kept as the floats that survive that.

#include <mr/core/types.h>

#include <array>
#include <cstdint>
#include <string>

namespace mr {

class CoordinateGrid {
 public:
  enum class Kind { doubles, float32, float32_about, quantized };

  /// Draco's position quantization: origin and range as stored in the file
  /// (a grid made from them holds them as they come out of Draco's options).
  struct Quantization {
    std::array<float, 3> origin{0.0f, 0.0f, 0.0f};
    float range = 1.0f;
    int bits = 16;  ///< 1 to 30
  };

  static CoordinateGrid doubles() { return CoordinateGrid(Kind::doubles, {}); }
  static CoordinateGrid float32() { return CoordinateGrid(Kind::float32, {}); }
  static CoordinateGrid quantized(const Quantization& quantization);
  /// Floats about `origin` in steps of `unit` (a power of two; `origin` a
  /// multiple of it, each coordinate below 2^52 units). Throws UsageError otherwise.
  static CoordinateGrid float32_about(const Vec3d& origin, double unit);
  /// The float32 grid a glTF writer stores positions inside [lo, hi] on:
  /// float32 itself, or, where its steps there are more than four times
  /// those of floats about the box's centre (a model away from the origin
  /// by more than a few of its sizes), floats about that centre.
  static CoordinateGrid float32_over(const Vec3d& lo, const Vec3d& hi);
  /// A quantization grid of `bits` covering the box [lo, hi] with a margin
  /// of a few steps on each side, so vertices moved by a few steps stay on it.
  static CoordinateGrid quantized_over(const Vec3d& lo, const Vec3d& hi, int bits);

  Kind kind() const { return kind_; }
  const Quantization& quantization() const { return quantization_; }
  /// float32_about: the origin the floats are relative to (else zero).
  const Vec3d& origin() const { return origin_; }
  /// True when every double is on the grid.
  bool is_identity() const { return kind_ == Kind::doubles; }
  /// "float64", "float32" or "16-bit quantization".
  std::string name() const;

  /// The grid value nearest to x on `axis` (for a quantized grid, clamped to its range).
  double nearest(int axis, double x) const;
  Vec3d nearest(const Vec3d& p) const;
  /// The grid value `steps` steps away from the grid value g on `axis`
  /// (negative: down); clamped at the ends of a quantized grid.
  double step(int axis, double g, int steps) const;
  /// True if p is on the grid and a file on it stores p as it is. (Draco's
  /// encoder quantizes in float arithmetic too: past about 20 bits it
  /// stores some grid values at a neighbouring level.)
  bool holds(const Vec3d& p) const;
  /// The largest distance between neighbouring grid values on any axis
  /// within the box [lo, hi] (found at its corners, where coordinates are
  /// largest): how far rounding may move a vertex there, doubled.
  double spacing_over(const Vec3d& lo, const Vec3d& hi) const;

 private:
  CoordinateGrid(Kind kind, const Quantization& quantization);
  double dequantize(int axis, std::int64_t q) const;
  std::int64_t encoded_level(int axis, double x) const;
  bool stored_as_is(int axis, double x) const;
  std::int64_t nearest_level(int axis, double x) const;
  double about_value(int axis, std::int64_t k) const;
  std::int64_t about_level(int axis, double x) const;

  Kind kind_;
  Quantization quantization_;
  float delta_ = 0.0f;          ///< quantized: the step, in float as Draco computes it
  float inverse_delta_ = 0.0f;  ///< quantized: levels per unit, in float as Draco's encoder computes it
  std::int64_t max_level_ = 0;
  Vec3d origin_ = Vec3d::Zero();  ///< float32_about
  double unit_ = 0.0;             ///< float32_about
};

}  // namespace mr
