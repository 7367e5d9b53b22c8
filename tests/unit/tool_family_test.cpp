// What every tool of the family shares: inputs without geometry are refused
// the same way by all (the rule lives in the I/O core's read path), and one
// option vocabulary (-q, -v, -j, --stats).

#include "extract_boundary.h"
#include "format_convert.h"
#include "hole_fill_tool.h"
#include "mesh_check.h"
#include "meshrepair.h"
#include "simplify_in_envelope.h"
#include "test_support.h"
#include "tetrahedralize.h"

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

using namespace mr;

namespace {

struct Tool {
  const char* name;
  test::ToolMain main;
  const char* output;  // an output file name of a kind the tool writes
};

const std::vector<Tool>& all_tools() {
  static const std::vector<Tool> tools{{"format-convert", tools::format_convert, "out.obj"},
                                       {"meshrepair", tools::meshrepair, "out.obj"},
                                       {"tetrahedralize", tools::tetrahedralize, "out.msh"},
                                       {"simplify-in-envelope", tools::simplify_in_envelope, "out.obj"},
                                       {"extract-boundary", tools::extract_boundary, "out.obj"},
                                       {"hole-fill", tools::hole_fill, "out.obj"},
                                       {"mesh-check", tools::mesh_check, ""}};
  return tools;
}

// IN, then OUT for the tools that write one.
std::vector<std::string> arguments(const Tool& tool, const std::filesystem::path& in,
                                   const test::TempDir& dir) {
  std::vector<std::string> args{in.string()};
  if (*tool.output) args.push_back((dir / tool.output).string());
  return args;
}

// Random bytes (a fixed sequence), as a file misnamed .obj would hold.
std::vector<char> random_bytes(std::size_t count) {
  std::vector<char> bytes(count);
  std::uint32_t state = 27;
  for (char& b : bytes) {
    state = state * 1664525u + 1013904223u;
    b = static_cast<char>(state >> 24);
  }
  return bytes;
}

// A binary STL: 80-byte header (not starting with "solid") and a count of 0.
std::vector<char> stl_without_facets() {
  std::vector<char> bytes(84, '\0');
  const std::string header = "binary STL with no facets";
  std::copy(header.begin(), header.end(), bytes.begin());
  return bytes;
}

}  // namespace

TEST_CASE("an input without triangles is refused by every tool, nothing written", "[tools][bad_input]") {
  test::TempDir dir("no_triangles");
  test::write_bytes(dir / "garbage.obj", random_bytes(4096));
  test::write_bytes(dir / "empty.stl", stl_without_facets());
  test::write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
  const std::vector<std::string> inputs{"garbage.obj", "empty.stl", "points.obj"};
  for (const Tool& tool : all_tools()) {
    for (const std::string& input : inputs) {
      INFO(tool.name << " " << input);
      const auto before = dir.files();
      const test::ToolRun run = test::run_tool(tool.main, arguments(tool, dir / input, dir));
      INFO(run.err);
      CHECK(run.exit_code == 2);
      CHECK(run.out.empty());  // mesh-check prints no report either
      // extract-boundary reads volumes only: a surface file is refused for its format first.
      const std::string problem =
          tool.main == tools::extract_boundary ? "is a surface format" : "no triangles found";
      CHECK_THAT(run.err, Catch::Contains((dir / input).string() + ": " + problem));
      CHECK(dir.files() == before);
    }
  }
}

TEST_CASE("a volume file without tets is refused as a volume and as a surface", "[tools][bad_input]") {
  test::TempDir dir("no_tets");
  test::write_text(
      dir / "nodes.msh",
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
      "$Elements\n0\n$EndElements\n");
  const std::string problem = (dir / "nodes.msh").string() + ": no tets found";
  for (const Tool& tool : all_tools()) {
    INFO(tool.name);
    const test::ToolRun run = test::run_tool(tool.main, arguments(tool, dir / "nodes.msh", dir));
    INFO(run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Contains(problem));
    CHECK(dir.files() == std::vector<std::string>{"nodes.msh"});
  }
}

TEST_CASE("an input whose triangles are all degenerate is still geometry", "[tools][bad_input]") {
  test::TempDir dir("degenerate_only");
  test::write_text(dir / "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
  const test::ToolRun run =
      test::run_format_convert({(dir / "flat.obj").string(), (dir / "flat.ply").string()});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK(io::read_surface(io::make_default_registry(), dir / "flat.ply").triangles.size() == 2);
}

TEST_CASE("every tool takes -q, -v, -j and --stats", "[tools][cli][slow]") {
  test::TempDir dir("option_vocabulary");
  const io::Registry registry = io::make_default_registry();
  io::write_surface(registry, test::cube_soup(), dir / "cube.obj");
  io::write_volume(registry, test::cube_tets(), dir / "cube.msh");
  for (const Tool& tool : all_tools()) {
    INFO(tool.name);
    const bool reads_volume = tool.main == tools::extract_boundary;
    const std::filesystem::path in = dir / (reads_volume ? "cube.msh" : "cube.obj");
    std::vector<std::string> args = arguments(tool, in, dir);
    const std::string help = test::run_tool(tool.main, {"--help"}).out;
    for (const char* option : {"-q, --quiet", "-v, --verbose", "-j, --threads N", "--stats FILE"})
      CHECK_THAT(help, Catch::Contains(option));

    std::vector<std::string> verbose = args;
    verbose.insert(verbose.end(), {"-v", "-j", "1", "--stats", (dir / "stats.json").string()});
    const test::ToolRun loud = test::run_tool(tool.main, verbose);
    INFO(loud.err);
    CHECK(loud.exit_code == 0);
    CHECK_FALSE((loud.out + loud.err).empty());
    CHECK(std::filesystem::file_size(dir / "stats.json") > 2);

    std::vector<std::string> quiet = args;
    quiet.insert(quiet.end(), {"-q", "-v", "--threads", "2"});
    const test::ToolRun silent = test::run_tool(tool.main, quiet);
    INFO(silent.err);
    CHECK(silent.exit_code == 0);
    CHECK(silent.out.empty());
    CHECK(silent.err.empty());
    std::filesystem::remove(dir / "stats.json");
  }
}

TEST_CASE("format-convert -v says which names were not UTF-8", "[tools][utf8]") {
  test::TempDir dir("verbose_names");
  test::write_text(dir / "latin1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl M\xE9tal\nf 1 2 3\n");
  const std::vector<std::string> args{(dir / "latin1.obj").string(), (dir / "out.ply").string()};
  CHECK(test::run_format_convert(args).err.empty());  // silent by default
  std::vector<std::string> verbose = args;
  verbose.push_back("-v");
  const test::ToolRun run = test::run_format_convert(verbose);
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Contains("region name 0 is not UTF-8; taken as Windows-1252: M\xC3\xA9tal"));
  CHECK_THAT(run.out, Catch::Contains("3 vertices, 1 faces"));
}
