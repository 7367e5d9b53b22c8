// extract-boundary: the boundary of a tet mesh, all of it, by label, or every
// interface, oriented outward; the tool's exit codes and messages.

#include "test_support.h"

#include <mr/check/surface_check.h>
#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/repair/tet_boundary.h>

#include <extract_boundary.h>

#include <catch2/catch.hpp>

#include <sstream>

using namespace mr;

namespace {

test::ToolRun run_extract_boundary(const std::vector<std::string>& args) {
  return test::run_tool(tools::extract_boundary, args);
}

repair::BoundaryRequest request(repair::BoundaryMode mode, std::int32_t label = 0) {
  repair::BoundaryRequest r;
  r.mode = mode;
  r.label = label;
  return r;
}

}  // namespace

TEST_CASE("the boundary of a cube of tets is its 12 outward faces", "[extract-boundary]") {
  const TriangleSoup soup = repair::tet_mesh_boundary(test::cube_tets(), {});
  REQUIRE(soup.triangles.size() == 12);
  REQUIRE(soup.positions.size() == 8);
  const check::SurfaceReport r = check::check_surface(soup);
  REQUIRE(r.watertight());
  REQUIRE(r.volume == Approx(1.0));
}

TEST_CASE("inverted tets are flipped before the boundary is taken", "[extract-boundary]") {
  TetMesh mesh = test::cube_tets();
  for (std::size_t t = 0; t < mesh.tets.size(); t += 2) std::swap(mesh.tets[t][0], mesh.tets[t][1]);
  std::size_t flipped = 0;
  const TetMesh positive = repair::with_positive_tets(mesh, &flipped);
  REQUIRE(flipped == 3);
  REQUIRE(test::tet_volume(positive) == Approx(1.0));
  const check::SurfaceReport r = check::check_surface(repair::tet_mesh_boundary(mesh, {}));
  REQUIRE(r.watertight());
  REQUIRE(r.volume == Approx(1.0));
}

TEST_CASE("the boundary of one label encloses only its tets", "[extract-boundary]") {
  const TetMesh mesh = test::cube_tets();  // labels 1..6, one per tet
  for (std::int32_t label = 1; label <= 6; ++label) {
    const TriangleSoup soup = repair::tet_mesh_boundary(mesh, request(repair::BoundaryMode::label, label));
    REQUIRE(soup.triangles.size() == 4);
    const check::SurfaceReport r = check::check_surface(soup);
    REQUIRE(r.watertight());
    REQUIRE(r.volume == Approx(1.0 / 6.0));
  }
  TetMesh two_labels = mesh;
  two_labels.tet_labels = {1, 1, 1, 2, 2, 2};
  const TriangleSoup half = repair::tet_mesh_boundary(two_labels, request(repair::BoundaryMode::label, 2));
  REQUIRE(check::check_surface(half).volume == Approx(0.5));
}

TEST_CASE("an unknown label is refused with the labels present", "[extract-boundary]") {
  try {
    repair::tet_mesh_boundary(test::cube_tets(), request(repair::BoundaryMode::label, 9));
    FAIL("no error");
  } catch (const UsageError& e) {
    REQUIRE(std::string(e.what()).find("label 9") != std::string::npos);
    REQUIRE(std::string(e.what()).find("1, 2, 3, 4, 5, 6") != std::string::npos);
  }
}

TEST_CASE("interfaces: the outer boundary and each face between labels once", "[extract-boundary]") {
  TetMesh mesh = test::cube_tets();
  TriangleSoup soup = repair::tet_mesh_boundary(mesh, request(repair::BoundaryMode::interfaces));
  REQUIRE(soup.triangles.size() == 12 + 6);  // the 6 Kuhn tets share 6 inner faces
  REQUIRE(soup.face_regions.size() == soup.triangles.size());
  mesh.tet_labels = {1, 1, 1, 2, 2, 2};
  soup = repair::tet_mesh_boundary(mesh, request(repair::BoundaryMode::interfaces));
  // The two halves meet in two inner faces.
  REQUIRE(soup.triangles.size() == 12 + 2);
  const check::SurfaceReport r = check::check_surface(soup);
  REQUIRE(r.nonmanifold_edges > 0);  // interfaces meet the outside along edges
  REQUIRE(r.self_intersecting_pairs == 0);
}

TEST_CASE("extract-boundary writes the outward boundary of a mesh file", "[extract-boundary]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("extract_boundary");
  TetMesh mesh = test::cube_tets();
  mesh.tet_labels = {1, 1, 1, 2, 2, 2};
  io::write_volume(registry, mesh, dir / "cube.msh");

  test::ToolRun run = run_extract_boundary({(dir / "cube.msh").string(), (dir / "all.stl").string()});
  CAPTURE(run.err);
  REQUIRE(run.exit_code == 0);
  REQUIRE(run.out.find("12 boundary faces") != std::string::npos);
  TriangleSoup soup = io::read_surface(registry, dir / "all.stl");
  REQUIRE(check::check_surface(soup).watertight());
  REQUIRE(check::check_surface(soup).volume == Approx(1.0));

  run = run_extract_boundary({(dir / "cube.msh").string(), (dir / "two.ply").string(), "--label", "2", "-q"});
  REQUIRE(run.exit_code == 0);
  REQUIRE(run.out.empty());
  REQUIRE(check::check_surface(io::read_surface(registry, dir / "two.ply")).volume == Approx(0.5));

  run =
      run_extract_boundary({(dir / "cube.msh").string(), (dir / "interfaces.obj").string(), "--interfaces"});
  REQUIRE(run.exit_code == 0);
  REQUIRE(io::read_surface(registry, dir / "interfaces.obj").triangles.size() == 14);
}

TEST_CASE("extract-boundary: bad input and usage exit with 2, write failures with 1", "[extract-boundary]") {
  const io::Registry registry = io::make_default_registry();
  test::TempDir dir("extract_boundary_bad");
  io::write_volume(registry, test::cube_tets(), dir / "cube.msh");
  io::write_surface(registry, test::cube_soup(), dir / "surface.stl");
  const std::string msh = (dir / "cube.msh").string();

  const auto missing = (dir / "missing.msh").string();
  test::ToolRun run = run_extract_boundary({missing, (dir / "out.stl").string()});
  REQUIRE(run.exit_code == 2);
  REQUIRE(run.err.find(missing) != std::string::npos);

  run = run_extract_boundary({(dir / "surface.stl").string(), (dir / "out.stl").string()});
  REQUIRE(run.exit_code == 2);
  REQUIRE(run.err.find("surface.stl") != std::string::npos);

  test::write_text(dir / "garbage.msh",
                   "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 999999999 1 999999999\n");
  run = run_extract_boundary({(dir / "garbage.msh").string(), (dir / "out.stl").string()});
  REQUIRE(run.exit_code == 2);
  REQUIRE(run.err.find("garbage.msh") != std::string::npos);

  run = run_extract_boundary({msh, (dir / "out.stl").string(), "--label", "7"});
  REQUIRE(run.exit_code == 2);
  REQUIRE(run.err.find("label 7") != std::string::npos);
  run = run_extract_boundary({msh, (dir / "out.stl").string(), "--label", "1", "--interfaces"});
  REQUIRE(run.exit_code == 2);
  run = run_extract_boundary({msh, (dir / "out.stl").string(), "--label", "x"});
  REQUIRE(run.exit_code == 2);

  run = run_extract_boundary({msh, (dir / "no_such_folder" / "out.stl").string()});
  REQUIRE(run.exit_code == 1);
  REQUIRE_FALSE(std::filesystem::exists(dir / "out.stl"));
}
