#include "test_support.h"

#include <mr/cli/options.h>
#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>

#include <catch2/catch.hpp>

#include <new>
#include <sstream>
#include <stdexcept>

using namespace mr;

TEST_CASE("option table parses flags, values and positionals", "[cli]") {
  double eps = 0;
  bool quiet = false;
  cli::ToolSpec spec{"tool", "does things", {"IN", "OUT"}, "", {}};
  spec.options = {
      {"--epsilon", "-e", "EPS", "envelope", [&](const std::string& v) { eps = cli::parse_double("-e", v); }},
      {"--quiet", "-q", "", "quiet", [&](const std::string&) { quiet = true; }}};
  const std::vector<std::string> args{"a.stl", "-e", "-1e-3", "-q", "b.stl"};
  CHECK(cli::parse_arguments(spec, args) == std::vector<std::string>{"a.stl", "b.stl"});
  CHECK(eps == -1e-3);
  CHECK(quiet);
  const std::vector<std::string> inline_value{"--epsilon=0.5", "a", "b"};
  cli::parse_arguments(spec, inline_value);
  CHECK(eps == 0.5);
  CHECK_THROWS_AS(cli::parse_arguments(spec, std::vector<std::string>{"a"}), UsageError);
  CHECK_THROWS_AS(cli::parse_arguments(spec, std::vector<std::string>{"a", "b", "--nope"}), UsageError);
  CHECK_THROWS_AS(cli::parse_arguments(spec, std::vector<std::string>{"a", "b", "-e"}), UsageError);
  CHECK_THROWS_AS(cli::parse_arguments(spec, std::vector<std::string>{"a", "b", "-e", "x"}), UsageError);
  CHECK_THAT(cli::help_text(spec), Catch::Contains("-e, --epsilon EPS"));
}

TEST_CASE("format-convert answers --help, --version and bad usage", "[cli][format-convert]") {
  auto help = test::run_format_convert({"--help"});
  CHECK(help.exit_code == 0);
  CHECK_THAT(help.out, Catch::Contains("Usage: format-convert IN OUT"));
  auto version = test::run_format_convert({"--version"});
  CHECK(version.exit_code == 0);
  CHECK_THAT(version.out, Catch::Contains("format-convert 0."));
  auto missing = test::run_format_convert({"only-one.stl"});
  CHECK(missing.exit_code == 2);
  auto unknown = test::run_format_convert({"a.stl", "b.stl", "--frobnicate"});
  CHECK(unknown.exit_code == 2);
  CHECK_THAT(unknown.err, Catch::Contains("--frobnicate"));
}

TEST_CASE("run_tool names the files and hides a library's raw message", "[cli]") {
  const cli::ToolSpec spec{"tool", "does things", {"IN", "OUT"}, "", {}};
  std::ostringstream out, err;
  const auto library_throws = [](const std::vector<std::string>&) {
    throw std::runtime_error("[json.exception.type_error.316] invalid UTF-8 byte at index 9: 0x6B");
  };
  CHECK(cli::run_tool(spec, {"in.obj", "out.glb"}, out, err, library_throws) == cli::exit_failure);
  CHECK(
      err.str() ==
      "tool: error: in.obj -> out.glb: the run failed on an unexpected library error: invalid UTF-8 byte at "
      "index 9: 0x6B\n");
  err.str("");
  const auto out_of_memory = [](const std::vector<std::string>&) { throw std::bad_alloc(); };
  CHECK(cli::run_tool(spec, {"in.obj", "out.glb"}, out, err, out_of_memory) == cli::exit_failure);
  CHECK(err.str() == "tool: error: in.obj -> out.glb: out of memory\n");
  err.str("");
  const auto bad_input = [](const std::vector<std::string>&) {
    throw InputError("in.obj", "no triangles found");
  };
  CHECK(cli::run_tool(spec, {"in.obj", "out.glb"}, out, err, bad_input) == cli::exit_bad_input);
  CHECK(err.str() == "tool: error: in.obj: no triangles found\n");
  err.str("");
  const auto failed_run = [](const std::vector<std::string>&) { throw RunError("cannot write out.glb"); };
  CHECK(cli::run_tool(spec, {"in.obj", "out.glb"}, out, err, failed_run) == cli::exit_failure);
  CHECK(err.str() == "tool: error: cannot write out.glb\n");
}
