#pragma once
// meshrepair's face provenance as the user gets it: the --provenance file
// and the figures of --stats and of the summary line.

#include <mr/check/provenance.h>

#include <nlohmann/json.hpp>

#include <string>

namespace mr::tools {

/// {"faces": N, "input_face": [...], "source": ["kept" | "recut" | "filled", ...]}.
void write_provenance_file(const std::string& path, const check::FaceProvenance& provenance);

/// Orders `surface`'s faces by region (stably, regions below 0 first), as
/// the glTF writer writes them, and `provenance`'s entries with them.
void order_faces_by_region(TriangleSoup& surface, check::FaceProvenance& provenance);

nlohmann::json provenance_figures(const check::ProvenanceSummary& summary);

/// "N input faces kept (P% of the area)".
std::string kept_phrase(const check::ProvenanceSummary& summary);

}  // namespace mr::tools
