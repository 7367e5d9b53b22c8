#include "provenance_output.h"

#include <mr/cli/run_tool.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <type_traits>

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

void order_faces_by_region(TriangleSoup& surface, check::FaceProvenance& provenance) {
  if (!surface.has_face_regions()) return;
  std::vector<std::size_t> order(surface.triangles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto group = [&](std::size_t f) { return std::max(surface.face_regions[f], -1); };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return group(a) < group(b); });
  const auto permuted = [&](const auto& values) {
    std::decay_t<decltype(values)> out;
    out.reserve(values.size());
    for (std::size_t f : order) out.push_back(values[f]);
    return out;
  };
  surface.triangles = permuted(surface.triangles);
  surface.face_regions = permuted(surface.face_regions);
  if (surface.has_face_sources()) surface.face_sources = permuted(surface.face_sources);
  provenance.input_face = permuted(provenance.input_face);
  provenance.source = permuted(provenance.source);
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
