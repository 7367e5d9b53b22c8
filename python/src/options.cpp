#include "options.h"

#include <mr/core/errors.h>

namespace mr::python {

CoordinateGrid grid_named(const std::string& name) {
  if (name == "float64") return CoordinateGrid::doubles();
  if (name == "float32") return CoordinateGrid::float32();
  throw UsageError("grid must be \"float64\" or \"float32\", got \"" + name + "\"");
}

int checked_threads(int threads) { return non_negative("threads", threads); }

int non_negative(const char* option, int value) {
  if (value < 0) throw UsageError(std::string(option) + " must be >= 0, got " + std::to_string(value));
  return value;
}

}  // namespace mr::python
