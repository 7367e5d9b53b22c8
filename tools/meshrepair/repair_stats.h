#pragma once
// The --stats JSON of meshrepair: defects of the input, figures of the
// output (measured independently with mr::check), and time per stage.

#include "holes_only_repair.h"
#include "outer_hull_path.h"
#include "surface_output.h"

#include <mr/check/provenance.h>
#include <mr/check/written_file.h>
#include <mr/core/triangle_soup.h>
#include <mr/hole_fill/hole_fill.h>
#include <mr/repair/repair.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mr::tools {

/// How keeping the input went (all empty under --remesh).
struct KeepInputOutcome {
  std::string abandoned;              ///< why it was given up for a rebuild (empty: it was not)
  int band_rings = -1;                ///< the defect band the input was kept with (-1: rebuilt)
  std::vector<std::string> gave_way;  ///< why each band that gave way did
  double seconds_gave_way = 0.0;      ///< what the bands that gave way cost
  double seconds_abandoned = 0.0;     ///< what the run that kept the input and failed cost
};

struct RepairRun {
  const TriangleSoup& input;
  const tetmesh::PipelineResult& pipeline;
  const repair::RepairResult& repair;
  const check::WrittenFileReport& written;
  const check::ProvenanceSummary& provenance;
  double seconds_read = 0.0;
  double seconds_hole_fill_tried = 0.0;  ///< the holes-only path (and the cut), until it declined
  double seconds_write = 0.0;
  std::string hole_fill_declined;  ///< why the holes-only path was not taken
  KeepInputOutcome keep_input;
  DefectCut defects_cut;            ///< the cut tried before the tets (declined)
  const OuterHull* hull = nullptr;  ///< rebuilt instead of the input (null: the input was)
};

nlohmann::json make_repair_stats(const RepairRun& run);

/// The holes-only path (holes_only_repair.h): input, holes, output figures, seconds.
struct HolesOnlyRun {
  const TriangleSoup& input;
  const HolesOnlyRepair& holes;  ///< with its fill
  const SurfaceWrite& written;
  const check::ProvenanceSummary& provenance;
  double epsilon = 0.0;  ///< the envelope the tetrahedral path would have used (sets Draco's bits)
  double seconds_read = 0.0;
  double seconds_fill = 0.0;
  double seconds_write = 0.0;
};

nlohmann::json make_holes_only_stats(const HolesOnlyRun& run);

}  // namespace mr::tools
