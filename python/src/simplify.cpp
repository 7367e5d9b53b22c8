// simplify(): the simplify-in-envelope tool on arrays.

#include "arrays.h"
#include "bindings.h"
#include "options.h"

#include <mr/simplify/simplify.h>

namespace mr::python {
namespace {

constexpr const char* kDoc =
    R"(Reduce the face count of a surface, keeping every point within epsilon of the input.

The simplify-in-envelope tool on arrays: edge collapses, then angle-improving
edge flips, each accepted only if every changed triangle stays inside the
epsilon-envelope of the input, no normal turns by more than the allowed
deviation and no new self-intersection appears (exact test). Output
positions are a subset of the input's. Deterministic for any thread count.

Args:
    vertices: (N, 3) array of real numbers.
    faces: (M, 3) array of integer vertex indices.
    epsilon: envelope radius relative to the bounding-box diagonal.
    epsilon_abs: absolute envelope radius; overrides epsilon when > 0.
    target_faces: stop at this many faces (0: as few as the envelope allows).
    max_normal_deviation: largest normal change of a face per operation, degrees.
    flip_passes: most sweeps of edge flips after collapsing (0: none).
    threads: worker threads; 0 uses all hardware threads.

Returns:
    (vertices, faces): float64 (N, 3) and int64 (M, 3) arrays.

Raises:
    ValueError: bad arrays or options.
)";

}  // namespace

void bind_simplify(py::module_& m) {
  const simplify::SimplifyOptions d;
  m.def(
      "simplify",
      [](const ArrayLike& vertices, const ArrayLike& faces, double epsilon, double epsilon_abs,
         int target_faces, double max_normal_deviation, int flip_passes, int threads) {
        const TriangleSoup input = soup_from_arrays(vertices, faces);
        simplify::SimplifyOptions options;
        options.epsilon_rel = epsilon;
        options.epsilon_abs = epsilon_abs;
        options.target_faces = static_cast<std::size_t>(non_negative("target_faces", target_faces));
        options.max_normal_deviation_deg = max_normal_deviation;
        options.flip_passes = non_negative("flip_passes", flip_passes);
        options.threads = checked_threads(threads);
        const TriangleSoup output =
            without_gil([&] { return simplify::simplify_in_envelope(input, options).soup; });
        return soup_to_arrays(output);
      },
      kDoc, py::arg("vertices"), py::arg("faces"), py::kw_only(), py::arg("epsilon") = d.epsilon_rel,
      py::arg("epsilon_abs") = d.epsilon_abs, py::arg("target_faces") = 0,
      py::arg("max_normal_deviation") = d.max_normal_deviation_deg, py::arg("flip_passes") = d.flip_passes,
      py::arg("threads") = d.threads);
}

}  // namespace mr::python
