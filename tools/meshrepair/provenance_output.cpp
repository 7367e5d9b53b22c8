#include "provenance_output.h"

#include <mr/cli/run_tool.h>

#include <cmath>

namespace mr::tools {
namespace {

const char* source_name(check::FaceSource source) {
  switch (source) {
    case check::FaceSource::kept:
      return "kept";
    case check::FaceSource::recut:
      return "recut";
    case check::FaceSource::filled:
      return "filled";
  }
  return "filled";
}

}  // namespace

void write_provenance_file(const std::string& path, const check::FaceProvenance& provenance) {
  nlohmann::json sources = nlohmann::json::array();
  for (check::FaceSource s : provenance.source) sources.push_back(source_name(s));
  const nlohmann::json json = {
      {"faces", provenance.input_face.size()}, {"input_face", provenance.input_face}, {"source", sources}};
  cli::write_stats_file(path, json.dump());
}

nlohmann::json provenance_figures(const check::ProvenanceSummary& summary) {
  return {{"kept_faces", summary.kept_faces},
          {"recut_faces", summary.recut_faces},
          {"filled_faces", summary.filled_faces},
          {"kept_area", summary.kept_area},
          {"recut_area", summary.recut_area},
          {"filled_area", summary.filled_area},
          {"kept_area_share", summary.kept_area_share()},
          {"input_triangles_kept", summary.input_triangles_kept}};
}

std::string kept_phrase(const check::ProvenanceSummary& summary) {
  const double percent = std::floor(1000.0 * summary.kept_area_share()) / 10.0;
  std::string text = std::to_string(summary.input_triangles_kept) + " input faces kept (";
  std::string number = std::to_string(percent);
  number.erase(number.find('.') + 2);
  return text + number + "% of the area)";
}

}  // namespace mr::tools
