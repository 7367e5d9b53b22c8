#include "surface_input.h"

#include <mr/core/errors.h>
#include <mr/kernel/predicates.h>

#include <algorithm>

namespace mr::tools {

void check_has_area(const std::filesystem::path& path, const TriangleSoup& input) {
  const auto& p = input.positions;
  const bool some_area = std::any_of(input.triangles.begin(), input.triangles.end(),
                                     [&](const auto& t) { return !collinear(p[t[0]], p[t[1]], p[t[2]]); });
  if (!some_area)
    throw InputError(path.string(),
                     "every triangle has zero area (collinear or repeated corners): there is "
                     "no surface to build a solid from");
}

}  // namespace mr::tools
