#pragma once
// The --stats JSON of meshrepair: defects of the input, figures of the
// output (measured independently with mr::check), and time per stage.

#include <mr/check/written_file.h>
#include <mr/core/triangle_soup.h>
#include <mr/repair/repair.h>
#include <mr/tetmesh/tetrahedralize.h>

#include <nlohmann/json.hpp>

namespace mr::tools {

struct RepairRun {
  const TriangleSoup& input;
  const tetmesh::PipelineResult& pipeline;
  const repair::RepairResult& repair;
  const check::WrittenFileReport& written;
  double seconds_read = 0.0;
  double seconds_write = 0.0;
};

nlohmann::json make_repair_stats(const RepairRun& run);

}  // namespace mr::tools
