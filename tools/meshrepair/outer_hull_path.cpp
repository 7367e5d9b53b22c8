#include "outer_hull_path.h"

#include "fast_path.h"

#include <mr/core/errors.h>
#if MR_HAVE_OUTER_HULL
#include <mr/volume/outer_hull_module.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>

namespace mr::tools {

std::size_t rebuild_budget_for(std::size_t faces, std::optional<std::size_t> requested) {
  if (!outer_hull_available()) return 0;
  return requested.value_or(rebuild_tet_budget(faces));
}

tetmesh::TetrahedralizeOptions hull_rebuild_options(const tetmesh::TetrahedralizeOptions& tetrahedralize,
                                                    const TriangleSoup& input) {
  tetmesh::TetrahedralizeOptions options = tetrahedralize;
  options.epsilon_abs = epsilon_for(input, tetrahedralize);
  return options;
}

#if MR_HAVE_OUTER_HULL

bool outer_hull_available() { return true; }

OuterHull outer_hull_of(const TriangleSoup& input, double epsilon) {
  const auto start = std::chrono::steady_clock::now();
  OuterHull hull;
  const double longest = used_bounding_box(input).sizes().maxCoeff();
  volume::OuterHullOptions options;
  // A probe on a coarse grid tells how many faces a finer one would make:
  // they grow as the inverse square of the voxel size.
  options.voxel_size = longest / kHullProbeVoxelsASide;
  const double probe_faces = double(volume::outer_hull_from_module(input, options).triangles.size());
  options.voxel_size = std::max({longest / kHullVoxelsASide, 0.5 * epsilon,
                                 options.voxel_size * std::sqrt(probe_faces / double(kHullMaxFaces))});
  hull.surface = volume::outer_hull_from_module(input, options);
  // Detail the probe smoothed away can still make too many.
  for (int coarser = 0; coarser < 2 && hull.surface.triangles.size() > kHullMaxFaces; ++coarser) {
    options.voxel_size *= 1.05 * std::sqrt(double(hull.surface.triangles.size()) / double(kHullMaxFaces));
    hull.surface = volume::outer_hull_from_module(input, options);
  }
  hull.voxel_size = options.voxel_size;
  hull.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return hull;
}

#else

bool outer_hull_available() { return false; }

OuterHull outer_hull_of(const TriangleSoup&, double) {
  throw RunError("this build has no outer hull (configured without OpenVDB: -DMR_WITH_VDB=OFF)");
}

#endif

}  // namespace mr::tools
