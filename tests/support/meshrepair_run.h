#pragma once
// Running meshrepair on a surface built in a test and reading its --stats.

#include "test_support.h"

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace mr::test {

/// Writes `input` as dir/in_name, runs meshrepair on it to dir/out_name with
/// --stats, requires exit 0 (printing stderr otherwise) and returns the stats.
inline nlohmann::json meshrepair_stats(const TriangleSoup& input, const TempDir& dir,
                                       const std::string& in_name, const std::string& out_name) {
  io::write_surface(io::make_default_registry(), input, dir / in_name);
  const ToolRun run = run_tool(tools::meshrepair, {(dir / in_name).string(), (dir / out_name).string(),
                                                   "--stats", (dir / "s.json").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  return nlohmann::json::parse(std::ifstream(dir / "s.json"));
}

}  // namespace mr::test
