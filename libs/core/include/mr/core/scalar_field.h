#pragma once
// A scalar function of space read from a file, such as the target edge
// length of `tetrahedralize --sizing` (a tet mesh with a value per node, or
// an OpenVDB grid). Implementations are immutable after construction and
// may be evaluated from several threads at once.

#include <mr/core/types.h>

namespace mr {

class ScalarField {
 public:
  virtual ~ScalarField() = default;
  /// The value at p; NaN where the field says nothing (outside its domain).
  virtual double at(const Vec3d& p) const = 0;
};

}  // namespace mr
