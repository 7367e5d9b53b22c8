#pragma once
// The whole meshrepair tool, run in-process on a tiny input: the entry point
// of the meshrepair fuzz target and of its regression files.
//
// The bytes are read as STL when they look like one (ASCII "solid" first, or
// the exact size of a binary STL), else as OBJ. Inputs that do not read, or
// hold more than pipeline_max_triangles triangles, are skipped, so that each
// run is fast. The rest go through `meshrepair IN OUT.stl -q -j 1` from a
// file; exit 0 (a watertight surface written) and exit 2 (an input error)
// pass. Exit 1 (a failed run, RunError or a library's exception) on an input
// that reads is a finding: run_meshrepair throws std::runtime_error with the
// tool's message.

#include "meshrepair.h"

#include <mr/core/errors.h>
#include <mr/io/mesh_io.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mr::fuzz {

inline constexpr std::size_t pipeline_max_triangles = 64;

/// "stl" or "obj": how the meshrepair target reads `bytes`.
inline std::string pipeline_input_format(std::string_view bytes) {
  if (bytes.substr(0, 5) == "solid") return "stl";
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, sizeof(count));
    if (84 + 50 * std::uint64_t{count} == bytes.size()) return "stl";
  }
  return "obj";
}

enum class PipelineOutcome { skipped, repaired, input_error };

struct PipelineRun {
  PipelineOutcome outcome = PipelineOutcome::skipped;
  double seconds = 0.0;  ///< of the meshrepair run alone
};

/// Runs meshrepair on `bytes` with its input and output files in `dir`
/// (which must exist), and removes them afterwards.
inline PipelineRun run_meshrepair(const io::Registry& registry, std::string_view bytes,
                                  const std::filesystem::path& dir) {
  const std::string format = pipeline_input_format(bytes);
  io::ReadOptions options;
  options.format = format;
  try {
    if (io::read_surface_bytes(registry, bytes, "fuzz." + format, options).triangles.size() >
        pipeline_max_triangles)
      return {};
  } catch (const InputError&) {
    return {};
  }
  const std::filesystem::path in = dir / ("in." + format), out = dir / "out.stl";
  {
    std::ofstream file(in, std::ios::binary);
    file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!file.flush()) throw std::runtime_error("cannot write " + in.string());
  }
  std::ostringstream out_text, err_text;
  const auto start = std::chrono::steady_clock::now();
  const int code = tools::meshrepair({in.string(), out.string(), "-q", "-j", "1"}, out_text, err_text);
  PipelineRun run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::error_code ec;
  std::filesystem::remove(in, ec);
  std::filesystem::remove(out, ec);
  if (code == 0) {
    run.outcome = PipelineOutcome::repaired;
  } else if (code == 2) {
    run.outcome = PipelineOutcome::input_error;
  } else {
    throw std::runtime_error("meshrepair exit " + std::to_string(code) + " on a readable " + format +
                             " input: " + err_text.str());
  }
  return run;
}

}  // namespace mr::fuzz
