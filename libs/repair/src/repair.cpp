#include <mr/repair/repair.h>

#include "boundary_defects.h"
#include "unbroken_triangles.h"

#include <mr/core/boundary.h>
#include <mr/core/errors.h>
#include <mr/core/weld.h>
#include <mr/envelope/envelope.h>
#include <mr/simplify/simplify.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace mr::repair {
namespace {

// The split copies of a vertex move at most this fraction of epsilon: far
// enough to stay apart when written as 32-bit floats, close enough to keep
// the surface where it was.
constexpr double kMoveFraction = 0.1;
// The tets at a defect are split to lie within this fraction of epsilon of
// it (manifold_fix.h), so fan edits there stay inside the envelope. Only
// for closed inputs: where the filter fills holes the surface leaves the
// envelope anyway, and on trimesh/soup (100 disjoint triangles, 32,727
// non-manifold edges) collars made 658k splits, doubled the surface and
// ran the fix out of rounds.
constexpr double kCollarFraction = 0.25;

bool is_closed(const TriangleSoup& input) {
  return detail::find_boundary_defects(weld_identical_vertices(input).triangles).boundary_edges == 0;
}

class StageClock {
 public:
  StageClock(RepairResult& result, std::string name)
      : result_(result), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
  ~StageClock() {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    result_.stages.push_back({name_, seconds});
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

 private:
  RepairResult& result_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
};

void check_arguments(const TetMesh& mesh, std::span<const std::uint8_t> inside, const TriangleSoup& input,
                     const RepairOptions& options) {
  if (!(options.epsilon > 0.0) || !std::isfinite(options.epsilon))
    throw UsageError("repair: epsilon must be finite and > 0");
  if (options.threads < 0) throw UsageError("repair: thread count must be >= 0");
  if (const std::string problem = find_tet_mesh_inconsistency(mesh); !problem.empty())
    throw UsageError("repair: inconsistent tet mesh: " + problem);
  if (const std::string problem = find_soup_inconsistency(input); !problem.empty())
    throw UsageError("repair: inconsistent input soup: " + problem);
  if (!inside.empty() && inside.size() != mesh.tets.size())
    throw UsageError("repair: " + std::to_string(inside.size()) + " inside flags for " +
                     std::to_string(mesh.tets.size()) + " tets");
  const bool any_inside = inside.empty()
                              ? !mesh.tets.empty()
                              : std::any_of(inside.begin(), inside.end(), [](auto f) { return f != 0; });
  if (!any_inside) throw RunError("repair: no tet was kept: the input encloses no volume");
}

// What the clean-up may move faces within epsilon of: the input, and for an
// open input the peeled faces that lie outside its envelope (the filled
// ones, where a soup or a hole left the filter no input to follow). Without
// them no face there could change: a soup's surface kept every sliver edge
// the arrangement of its triangles made, down to 1e-9 long, and no float32
// position was left for its vertices. A closed input's output must stay
// within epsilon of it, so there the input alone is the reference (faces
// near the envelope's edge count as outside: trimesh/Duck went to 1.09 eps).
TriangleSoup clean_up_reference(const TriangleSoup& peeled, const TriangleSoup& input, bool input_closed,
                                const envelope::Envelope& input_envelope) {
  TriangleSoup reference;
  reference.positions = input.positions;
  reference.triangles = input.triangles;
  if (input_closed) return reference;
  const std::vector<std::uint8_t> inside = input_envelope.are_inside(peeled);
  const Index offset = static_cast<Index>(reference.positions.size());
  reference.positions.insert(reference.positions.end(), peeled.positions.begin(), peeled.positions.end());
  for (std::size_t f = 0; f < peeled.triangles.size(); ++f)
    if (!inside[f]) {
      const Triangle& t = peeled.triangles[f];
      reference.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
  return reference;
}

// What the clean-up must keep of the input triangles put back.
struct KeptTriangles {
  std::vector<std::uint8_t> frozen;              ///< per face of the surface: made from an input triangle
  std::vector<std::array<Index, 2>> fan_merges;  ///< see detail::UnbrokenTriangles
};

TriangleSoup clean_up(const TriangleSoup& peeled, KeptTriangles kept, const TriangleSoup& input,
                      bool input_closed, const envelope::Envelope& envelope, const RepairOptions& options,
                      RepairResult& result) {
  simplify::SimplifyOptions simplify_options;
  simplify_options.epsilon_abs = options.epsilon;
  simplify_options.threads = options.threads;
  simplify_options.frozen_faces = std::move(kept.frozen);
  simplify_options.frozen_merges = std::move(kept.fan_merges);
  simplify::SimplifyResult simplified = simplify::simplify_in_envelope_of(
      peeled, clean_up_reference(peeled, input, input_closed, envelope), simplify_options);
  result.collapses = simplified.collapses;
  result.flips = simplified.flips;
  return std::move(simplified.soup);
}

// How far a peeled vertex may lie from an input triangle and still count as
// on it: cut points were rounded to doubles, a few units in the last place
// of the coordinates; far below epsilon either way.
double on_input_tolerance(const TriangleSoup& surface, double epsilon) {
  double largest = 0.0;
  for (const Vec3d& p : surface.positions) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  return std::max(1e-6 * epsilon, 64.0 * std::numeric_limits<double>::epsilon() * largest);
}

// The input triangles the peeled faces tile put back; flags the faces made
// from them, which the clean-up must keep.
KeptTriangles keep_input_triangles(const TriangleSoup& input, const RepairOptions& options,
                                   RepairResult& result) {
  const TriangleSoup& inserted = options.inserted_input ? *options.inserted_input : input;
  detail::UnbrokenTriangles kept =
      detail::put_back_unbroken_triangles(result.surface, inserted, input, options.inserted_snap_spacing,
                                          on_input_tolerance(result.surface, options.epsilon));
  result.surface = std::move(kept.surface);
  result.input_triangles_put_back = kept.put_back;
  KeptTriangles out;
  out.frozen.resize(kept.origins.size());
  for (std::size_t f = 0; f < out.frozen.size(); ++f)
    out.frozen[f] = kept.origins[f] != detail::FaceOrigin::peeled;
  out.fan_merges = std::move(kept.fan_merges);
  return out;
}

// The manifold fix edits a copy of the tets; the copy is dropped once its
// boundary is peeled, before the clean-up needs memory of its own.
void peel_manifold_boundary(const TetMesh& mesh, std::span<const std::uint8_t> inside,
                            const envelope::Envelope* envelope, bool input_closed,
                            const RepairOptions& options, RepairResult& result) {
  TetMesh work;
  work.positions = mesh.positions;
  work.tets = mesh.tets;
  {
    StageClock clock(result, "manifold");
    ManifoldFixOptions fix;
    fix.max_move = kMoveFraction * options.epsilon;
    fix.collar_width = input_closed ? kCollarFraction * options.epsilon : 0.0;
    fix.max_rounds = options.max_manifold_rounds;
    result.manifold = make_boundary_manifold(work, inside, envelope, fix);
  }
  StageClock clock(result, "peel");
  result.surface = extract_boundary(work);
  result.peeled_faces = result.surface.triangles.size();
}

void round_to_output_grid(const RepairOptions& options, RepairResult& result) {
  StageClock clock(result, "round");
  const Eigen::AlignedBox3d box = bounding_box(result.surface);
  FinerGrid finer;
  if (options.finer_output_grid)
    finer = [&](const CoordinateGrid& refused) {
      return options.finer_output_grid(box.min(), box.max(), refused);
    };
  GridRounding rounded = round_to_grid_or_finer(result.surface, options.output_grid(box.min(), box.max()),
                                                finer, options.rounding);
  result.grid = rounded.grid;
  result.rounding = rounded.stats;
  result.finer_grids = rounded.finer_grids;
}

// The clean-up, then the rounding to the output grid. A fan merged back
// into its triangle stretches the rebuilt faces beside it to the
// triangle's corners, which can leave the rounding no room there
// (thingi10k/908460 jittered: 3 vertices found no float32 place); the
// clean-up then runs again from the peeled surface with the fans kept.
void clean_up_and_round(const TriangleSoup& input, bool input_closed, const envelope::Envelope& envelope,
                        KeptTriangles kept, const RepairOptions& options, RepairResult& result) {
  const bool may_retry = !kept.fan_merges.empty() && options.output_grid;
  const TriangleSoup peeled = may_retry ? result.surface : TriangleSoup{};
  KeptTriangles without_merges{may_retry ? kept.frozen : std::vector<std::uint8_t>{}, {}};
  const auto clean = [&](KeptTriangles faces) {
    StageClock clock(result, "cleanup");
    result.surface =
        clean_up(result.surface, std::move(faces), input, input_closed, envelope, options, result);
  };
  clean(std::move(kept));
  if (!options.output_grid) return;
  try {
    round_to_output_grid(options, result);
  } catch (const RunError&) {
    if (!may_retry) throw;
    result.surface = peeled;
    result.fan_merges_undone = true;
    clean(std::move(without_merges));
    round_to_output_grid(options, result);
  }
}

}  // namespace

RepairResult repair_surface_from_tets(const TetMesh& mesh, std::span<const std::uint8_t> inside,
                                      const TriangleSoup& input, const RepairOptions& options) {
  check_arguments(mesh, inside, input, options);
  RepairResult result;
  const bool input_closed = is_closed(input);  // welds the input: once
  std::unique_ptr<envelope::Envelope> envelope;
  if (!input.triangles.empty()) {
    envelope::EnvelopeOptions envelope_options;
    envelope_options.epsilon = options.epsilon;
    envelope = envelope::make_envelope(input, envelope_options);
  }
  peel_manifold_boundary(mesh, inside, envelope.get(), input_closed, options, result);
  KeptTriangles kept;
  if (options.keep_input_triangles && !input.triangles.empty()) {
    StageClock clock(result, "keep");
    kept = keep_input_triangles(input, options, result);
  }
  if (options.cleanup && !input.triangles.empty())
    clean_up_and_round(input, input_closed, *envelope, std::move(kept), options, result);
  else if (options.output_grid)
    round_to_output_grid(options, result);
  if (!detail::find_boundary_defects(result.surface.triangles).closed_manifold())
    throw RunError("repair: internal error: the repaired surface is not a closed manifold");
  return result;
}

}  // namespace mr::repair
