#pragma once
// The whole tetrahedralization pipeline of DESIGN.md (stages 1 to 7) behind
// one call: simplify the input inside the envelope, build the background
// mesh, insert every input triangle exactly, improve the mesh, filter by the
// winding number. Tools (tetrahedralize, meshrepair) are thin wrappers.

#include <mr/core/scalar_field.h>
#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>
#include <mr/tetmesh/logger.h>
#include <mr/tetmesh/options.h>
#include <mr/tetmesh/stats.h>

#include <memory>
#include <string_view>

namespace mr::tetmesh {

/// How the kept tets are labelled (PipelineResult::mesh.tet_labels).
enum class TetLabels {
  automatic,   ///< parts when the input has two face regions or more, else none
  none,        ///< label 1 on every tet
  parts,       ///< by the input's face regions (glTF materials, OBJ groups): region id + 1
  components,  ///< by connected component of the input: 1, 2, ... in order of first face
  winding,     ///< by the input's winding number rounded: nesting or overlap depth, at least 1
};

/// The mode named "auto", "none", "regions", "components" or "winding";
/// throws mr::UsageError for another name.
TetLabels tet_labels_named(std::string_view name);

struct PipelineOptions {
  TetrahedralizeOptions tetrahedralize;
  /// Keep only the tets inside (winding number); false keeps every tet of
  /// the box and labels each with its region (tets connected without
  /// crossing the tracked surface), for multi-material inputs.
  bool filter = true;
  /// With filter: return the tets it rejected too, labelled 0 (kept tets 1),
  /// for meshrepair's manifold fix, which may add some of them.
  bool keep_rejected = false;
  /// Labels of the kept tets (with filter, without keep_rejected). Each set
  /// of tets connected without crossing the tracked surface gets the label
  /// of the part most inside it (see part_labels.h).
  TetLabels labels = TetLabels::automatic;
  /// Run the mesh-improvement stage. meshrepair's fast path turns it off:
  /// it needs a valid embedding, not well-shaped tets.
  bool improve = true;
  /// Target edge length varying in space for improvement
  /// (ImproveOptions::sizing; tetrahedralize --sizing); null: uniform.
  std::shared_ptr<const ScalarField> sizing;
};

struct PipelineResult {
  /// Doubles only, every tet positively oriented on these doubles (checked
  /// exactly before returning). With filter: the label of each kept tet's
  /// part (PipelineOptions::labels; 1 without parts), or 1 on kept tets and
  /// 0 on rejected ones with keep_rejected; without: the region label of
  /// each tet.
  TetMesh mesh;
  /// The tracked surface: the mesh faces the input triangles were inserted
  /// as (after improvement), restricted to the kept tets when filtering.
  /// Oriented as the input triangle it came from.
  TriangleSoup tracked_surface;
  /// The surface as inserted: oriented, simplified unless skipped, snapped
  /// onto a grid of `snap_spacing` (0: not snapped); its positions are
  /// input positions so snapped, unless it was thickened.
  TriangleSoup inserted_surface;
  double snap_spacing = 0.0;
  DerivedParameters parameters;
  PipelineStats stats;
};

/// Runs the pipeline. Throws mr::UsageError on bad options, mr::RunError
/// when the input has nothing to mesh or an internal check fails (the
/// result is never returned unchecked).
PipelineResult tetrahedralize(const TriangleSoup& input, const PipelineOptions& options,
                              const Logger& logger = {});

}  // namespace mr::tetmesh
