// Our glTF output must pass the Khronos glTF validator with zero errors.
// The validator is the npm package gltf-validator, installed in tests/tools:
//   npm ci --prefix tests/tools
// and run by tests/tools/validate_gltf.mjs with `node` from PATH.

#include "test_support.h"

#include <mr/io/mesh_io.h>
#include <mr/plugins/gltf_formats.h>

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace mr;

namespace {

const std::filesystem::path tools_dir = test::tools_dir();

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Built with += only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";
  text += path.string();
  text += "'";
  return text;
}

// Runs the validator on `files`; returns its exit code and fills `report`.
int run_validator(const std::vector<std::filesystem::path>& files, const test::TempDir& dir,
                  std::string& report) {
  std::string command = "node ";
  command += quoted(tools_dir / "validate_gltf.mjs");
  for (const auto& file : files) {
    command += ' ';
    command += quoted(file);
  }
  command += " > ";
  command += quoted(dir / "report.txt");
  command += " 2>&1";
  const int status = std::system(command.c_str());
  report = read_text(dir / "report.txt");
  return status;
}

TriangleSoup cube_with_everything() {
  TriangleSoup soup = test::cube_soup();
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    soup.normals.push_back((soup.positions[i] - Vec3d(0.5, 0.5, 0.5)).normalized().cast<float>());
    soup.uvs.emplace_back(static_cast<float>(soup.positions[i].x()),
                          static_cast<float>(soup.positions[i].y()));
    soup.colors.emplace_back(0.25f, 0.5f, 0.75f, 1.0f);
  }
  soup.normals[3] = Vec3f::Zero();  // the writer must repair it: the validator rejects non-unit normals
  soup.face_regions = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
  soup.region_names = {"bottom", "sides", "top"};
  return soup;
}

}  // namespace

TEST_CASE("written glTF, GLB and Draco GLB pass the Khronos validator", "[gltf][validator]") {
  const std::filesystem::path script = tools_dir / "validate_gltf.mjs";
  REQUIRE(std::filesystem::exists(script));
  if (std::system("node --version > /dev/null 2>&1") != 0)
    FAIL(
        "node is not on PATH: install Node.js (apt-get install nodejs npm), then npm ci --prefix "
        "tests/tools");
  if (!std::filesystem::exists(tools_dir / "node_modules" / "gltf-validator"))
    FAIL("the glTF validator is missing: run  npm ci --prefix " + tools_dir.string());

  io::Registry registry;
  plugins::register_gltf_formats(registry);
  test::TempDir dir("gltf_validator");
  const TriangleSoup cube = cube_with_everything();
  io::write_surface(registry, cube, dir / "cube.glb");
  io::write_surface(registry, cube, dir / "cube.gltf");
  io::write_surface(registry, test::cube_soup(), dir / "plain.glb");
  std::vector<std::filesystem::path> files{dir / "cube.glb", dir / "cube.gltf", dir / "plain.glb"};
#if __has_include(<mr/plugins/draco_codec.h>)  // built with Draco (MR_WITH_DRACO)
  io::WriteOptions draco;
  draco.draco.compress_gltf = true;
  io::write_surface(registry, cube, dir / "cube_draco.glb", draco);
  files.push_back(dir / "cube_draco.glb");
#endif

  std::string report;
  const int status = run_validator(files, dir, report);
  INFO(report);
  CHECK(status == 0);
  CHECK(report.find("\"numErrors\": 0") != std::string::npos);
}

TEST_CASE("the validator runner fails on a broken file", "[gltf][validator]") {
  test::TempDir dir("gltf_validator_control");
  test::write_text(dir / "broken.gltf", R"({"asset": {"version": "2.0"}, "scene": 3})");
  std::string report;
  const int status = run_validator({dir / "broken.gltf"}, dir, report);
  INFO(report);
  CHECK(status != 0);
}

TEST_CASE("an OBJ with Latin-1 names converts to a GLB the validator accepts", "[gltf][validator][utf8]") {
  if (!std::filesystem::exists(tools_dir / "node_modules" / "gltf-validator"))
    FAIL("the glTF validator is missing: run  npm ci --prefix " + tools_dir.string());
  test::TempDir dir("gltf_latin1_names");
  // A tetrahedron in two materials: "Métal" in Latin-1 (0xE9), and 0xE9
  // followed by 'k' (0x6B), a UTF-8 lead byte without its continuation.
  test::write_text(dir / "latin1.obj",
                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng caf\xE9\nusemtl M\xE9tal\nf 1 3 2\nf 1 2 4\n"
                   "usemtl \xE9"
                   "k\nf 1 4 3\nf 2 3 4\n");
  const std::vector<std::string> utf8_names{"M\xC3\xA9tal",
                                            "\xC3\xA9"
                                            "k"};
  const auto run = test::run_format_convert({(dir / "latin1.obj").string(), (dir / "latin1.glb").string()});
  INFO(run.err);
  REQUIRE(run.exit_code == 0);

  std::string report;
  const int status = run_validator({dir / "latin1.glb"}, dir, report);
  INFO(report);
  CHECK(status == 0);
  CHECK(report.find("\"numErrors\": 0") != std::string::npos);

  io::Registry registry;
  plugins::register_gltf_formats(registry);
  const TriangleSoup back = io::read_surface(registry, dir / "latin1.glb");
  CHECK(back.region_names == utf8_names);
  CHECK(back.face_regions == std::vector<std::int32_t>{0, 0, 1, 1});
}
