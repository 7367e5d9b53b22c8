#pragma once
// Per-stage statistics of a pipeline run (counts and seconds), written as
// JSON for tools and benchmarks.

#include <mr/tetmesh/logger.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
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

struct PipelineStats {
  std::vector<StageStats> stages;

  /// The stage named `name`, appended if absent.
  StageStats& stage(const std::string& name);
  double total_seconds() const;
};

/// {"stages": [{"name": ..., "seconds": ..., "counts": {...}}, ...],
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
