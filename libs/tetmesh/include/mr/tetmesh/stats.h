#pragma once
// Per-stage statistics of a pipeline run (counts and seconds), written as
// JSON for tools and benchmarks.

#include <mr/tetmesh/logger.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mr::tetmesh {

struct StageStats {
  std::string name;
  double seconds = 0.0;
  /// Named counts in insertion order (e.g. {"tets", 1234}).
  std::vector<std::pair<std::string, std::int64_t>> counts;

  void count(std::string key, std::int64_t value) { counts.emplace_back(std::move(key), value); }
};

/// A written tet that improvement left at or above the stop energy.
struct StuckTet {
  double amips = 0.0;
  std::array<double, 3> centroid{};
  std::string held_by;  ///< "free", "sliding", "creased" or "fixed" (StuckReport)
};

/// The written tets improvement left at or above the stop energy, each
/// counted by the freest of its corners: where the target was not reached,
/// and what held the operations back there.
struct StuckReport {
  std::size_t tets = 0;
  /// A corner may move anywhere: no operation found a better mesh.
  std::size_t free = 0;
  /// Every corner on the tracked surface or the box, some sliding along it.
  std::size_t sliding = 0;
  /// Every corner on a crease or an open boundary, moving only where its
  /// tets are bad (a crease's vertices stay on their input triangles).
  std::size_t creased = 0;
  /// No corner may move: on the input's open boundary, where parts meet or
  /// cross, on a box edge, or locked.
  std::size_t fixed = 0;
  std::vector<StuckTet> worst;  ///< the worst few, worst first
};

struct PipelineStats {
  std::vector<StageStats> stages;
  /// Filled when the pipeline improved the mesh.
  std::optional<StuckReport> stuck;

  /// The stage named `name`, appended if absent.
  StageStats& stage(const std::string& name);
  double total_seconds() const;
};

/// {"stages": [{"name": ..., "seconds": ..., "counts": {...}}, ...],
///  "stuck_tets": {"tets": ..., "free": ..., ..., "worst": [{"amips": ...,
///  "centroid": [x, y, z], "held_by": ...}, ...]} (when improved),
///  "total_seconds": ...}, indented by 2.
std::string to_json(const PipelineStats& stats);

/// Times a scope into stats.stage(name).seconds (added, so a stage may run
/// several times) and logs its start and end at debug level.
class StageTimer {
 public:
  StageTimer(PipelineStats& stats, std::string name, const Logger& logger);
  ~StageTimer();
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  StageStats& stage() { return stats_.stage(name_); }
  /// stage().count(key, value), for the sizes stages count.
  void count(std::string key, std::size_t value) {
    stage().count(std::move(key), static_cast<std::int64_t>(value));
  }

 private:
  PipelineStats& stats_;
  std::string name_;
  const Logger& logger_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mr::tetmesh
