// --max-memory refuses inputs before the run allocates for them; outputs are
// written through unnamed files, and files left unfinished by a signal are removed.

#include "mesh_generators.h"
#include "meshrepair.h"
#include "test_support.h"
#include "tetrahedralize.h"

#include <mr/io/atomic_file.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/io/unfinished_files.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace mr;

namespace {

// exit 2, the file and --max-memory named, nothing written.
void expect_refused(test::ToolMain tool, const std::filesystem::path& in, const std::filesystem::path& out,
                    const std::string& megabytes, const std::string& what) {
  const test::ToolRun run = test::run_tool(tool, {in.string(), out.string(), "--max-memory", megabytes});
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err,
             Catch::Contains(in.string()) && Catch::Contains("--max-memory") && Catch::Contains(what));
  CHECK_FALSE(std::filesystem::exists(out));
}

}  // namespace

TEST_CASE("an input too large for --max-memory is refused before the run", "[limits][slow]") {
  test::TempDir dir("max_memory");
  const io::Registry registry = io::make_default_registry();
  // 8 * 4^5 = 8,192 faces: 400 KB as binary STL, and about 6 MB at 768 bytes per face.
  io::write_surface(registry, test::sphere(1.0, 5), dir / "sphere.stl");
  for (test::ToolMain tool : {test::ToolMain(tools::meshrepair), test::ToolMain(tools::tetrahedralize)}) {
    const std::string out = tool == test::ToolMain(tools::meshrepair) ? "out.glb" : "out.msh";
    expect_refused(tool, dir / "sphere.stl", dir / out, "1", "8192 faces would need about 6 MB");
  }
  // A file larger than the budget is refused before it is read.
  io::write_surface(registry, test::sphere(1.0, 7), dir / "large.stl");  // 131,072 faces, 6.3 MB
  expect_refused(tools::meshrepair, dir / "large.stl", dir / "large.glb", "2", "the file is 7 MB");
  // Within the budget, the same input runs.
  CHECK(test::run_tool(tools::meshrepair, {(dir / "sphere.stl").string(), (dir / "out.glb").string(), "-q",
                                           "--max-memory", "64"})
            .exit_code == 0);
}

TEST_CASE("an output is written through an unnamed file and appears complete or not at all", "[io][limits]") {
  test::TempDir dir("unnamed_write");
  const std::filesystem::path out = dir / "out.txt";
  io::write_atomically(out, [&](const std::filesystem::path& path) {
    std::ofstream(path) << "complete";
    CHECK(dir.files().empty());  // nothing has a name while it is written
  });
  CHECK(dir.files() == std::vector<std::string>{"out.txt"});
  CHECK_THROWS(io::write_atomically(out, [](const std::filesystem::path& path) {
    std::ofstream(path) << "partial";
    throw std::runtime_error("stopped");
  }));
  std::ifstream in(out);
  std::string text;
  in >> text;
  CHECK(text == "complete");
  CHECK(dir.files() == std::vector<std::string>{"out.txt"});
}

TEST_CASE("files listed as unfinished are removed on request, and only while listed", "[io][limits]") {
  test::TempDir dir("unfinished");
  test::write_text(dir / "a.tmp", "a");
  test::write_text(dir / "b.tmp", "b");
  {
    const io::UnfinishedFile a(dir / "a.tmp");
    { const io::UnfinishedFile b(dir / "b.tmp"); }  // b finished: no longer listed
    io::remove_unfinished_files();
  }
  CHECK(dir.files() == std::vector<std::string>{"b.tmp"});
}
