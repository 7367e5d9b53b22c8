#include <mr/tetmesh/stats.h>

#include <nlohmann/json.hpp>

namespace mr::tetmesh {

StageStats& PipelineStats::stage(const std::string& name) {
  for (StageStats& s : stages) {
    if (s.name == name) return s;
  }
  stages.push_back(StageStats{name, 0.0, {}});
  return stages.back();
}

double PipelineStats::total_seconds() const {
  double total = 0.0;
  for (const StageStats& s : stages) total += s.seconds;
  return total;
}

std::string to_json(const PipelineStats& stats) {
  nlohmann::ordered_json root;
  root["stages"] = nlohmann::ordered_json::array();
  for (const StageStats& s : stats.stages) {
    nlohmann::ordered_json stage;
    stage["name"] = s.name;
    stage["seconds"] = s.seconds;
    stage["counts"] = nlohmann::ordered_json::object();
    for (const auto& [key, value] : s.counts) stage["counts"][key] = value;
    root["stages"].push_back(std::move(stage));
  }
  if (stats.stuck) {
    const StuckReport& stuck = *stats.stuck;
    nlohmann::ordered_json out;
    out["tets"] = stuck.tets;
    out["free"] = stuck.free;
    out["sliding"] = stuck.sliding;
    out["creased"] = stuck.creased;
    out["fixed"] = stuck.fixed;
    out["worst"] = nlohmann::ordered_json::array();
    for (const StuckTet& t : stuck.worst) {
      nlohmann::ordered_json tet;
      tet["amips"] = t.amips;
      tet["centroid"] = t.centroid;
      tet["held_by"] = t.held_by;
      out["worst"].push_back(std::move(tet));
    }
    root["stuck_tets"] = std::move(out);
  }
  root["total_seconds"] = stats.total_seconds();
  return root.dump(2);
}

StageTimer::StageTimer(PipelineStats& stats, std::string name, const Logger& logger)
    : stats_(stats), name_(std::move(name)), logger_(logger), start_(std::chrono::steady_clock::now()) {
  stats_.stage(name_);
  logger_.log(LogLevel::debug, "start " + name_);
}

StageTimer::~StageTimer() {
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
  stats_.stage(name_).seconds += elapsed.count();
  // A destructor must not throw: a failing logger loses this one message.
  try {
    logger_.log(LogLevel::debug, "end " + name_ + " (" + std::to_string(elapsed.count()) + " s)");
  } catch (...) {
  }
}

}  // namespace mr::tetmesh
