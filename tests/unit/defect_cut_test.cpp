// meshrepair's cut of local defects: the faces that are defects, and a band
// around them, taken out and the holes filled; every other face kept bit for
// bit, no tets. Crossing parts are not cut: they go through the tets.
#include "file_checks.h"
#include "mesh_generators.h"
#include "meshrepair_run.h"
#include "test_support.h"

#include <mr/check/self_intersections.h>
#include <mr/check/surface_check.h>
#include <mr/core/weld.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>
#include <mr/spatial/defect_faces.h>

#include <defect_cut.h>
#include <meshrepair.h>

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <set>

using namespace mr;

namespace {

// A sphere with a fold: one vertex of valence six moved along the surface
// past its neighbour, so that its fan folds over the faces beyond.
TriangleSoup sphere_with_fold(Index& moved) {
  TriangleSoup soup = test::sphere(1.0, 5);
  const Vec3d target = Vec3d(0.6, 0.64, 0.48).normalized();
  moved = 0;
  for (Index v = 1; v < soup.positions.size(); ++v)
    if ((soup.positions[v] - target).norm() < (soup.positions[moved] - target).norm()) moved = v;
  Index neighbour = moved;
  for (const Triangle& t : soup.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[i] == moved) neighbour = t[(i + 1) % 3];
  const Vec3d p = soup.positions[moved];
  soup.positions[moved] = (p + 1.6 * (soup.positions[neighbour] - p)).normalized();
  return soup;
}

nlohmann::json repaired(const TriangleSoup& input, const test::TempDir& dir, const std::string& out) {
  return test::meshrepair_stats(input, dir, "in.obj", out);
}

}  // namespace

TEST_CASE("a fold is cut out and filled, every face away from it kept bit for bit", "[defect_cut][e2e]") {
  Index moved = 0;
  const TriangleSoup input = sphere_with_fold(moved);
  REQUIRE(check::count_self_intersections(input) > 0);
  const test::TempDir dir("defect_cut_fold");
  const nlohmann::json stats = repaired(input, dir, "out.obj");
  REQUIRE(stats["path"] == "cut_and_fill");
  REQUIRE(stats["written_file"]["watertight"] == true);
  const std::size_t cut = stats["defects_cut"]["cut_faces"];
  CHECK(cut < 40);
  CHECK(stats["provenance"]["kept_area_share"] > 0.99);

  // OBJ keeps doubles: every face that is not within the cut band is in the
  // output as it was.
  std::vector<std::uint8_t> band = spatial::defect_faces(input);
  spatial::grow_by_vertex_rings(input, stats["defects_cut"]["rings"], band);
  REQUIRE(static_cast<std::size_t>(std::count(band.begin(), band.end(), 1)) == cut);
  TriangleSoup away = input;
  away.triangles.clear();
  for (std::size_t f = 0; f < input.triangles.size(); ++f)
    if (!band[f]) away.triangles.push_back(input.triangles[f]);
  const std::multiset<test::PositionTriple> output =
      test::position_triples(io::read_surface(io::make_default_registry(), dir / "out.obj"));
  for (const test::PositionTriple& face : test::position_triples(away)) REQUIRE(output.count(face) == 1);
}

TEST_CASE("parts that cross are not cut apart: they are joined through the tets", "[defect_cut][e2e]") {
  TriangleSoup input = test::sphere(1.0, 3);
  TriangleSoup other = test::sphere(1.0, 3);
  for (Vec3d& p : other.positions) p.x() += 1.0;
  input.append(other);
  const TriangleSoup welded = weld_identical_vertices(input);
  tools::DefectCutOptions options;
  options.epsilon = 1e-3 * 3.0;
  const tools::DefectCut cut = tools::cut_out_defects(welded, options);
  REQUIRE(!cut.fill);
  CHECK(cut.defect_faces > 0);
  CHECK(cut.local);
  // Not a band is tried: cut out and filled, each sphere would close on its
  // own and still overlap the other.
  CHECK(cut.declined == "parts cross each other");

  const test::TempDir dir("defect_cut_crossing");
  const nlohmann::json stats = repaired(input, dir, "out.glb");
  REQUIRE(stats["path"] == "tetrahedralize");
  REQUIRE(stats["output"]["components"] == 1);  // the union, not two shells
  REQUIRE(stats["written_file"]["watertight"] == true);
  // The tet path reports the cut it tried, and what trying cost.
  CHECK(stats["defects_cut"]["defect_faces"] == cut.defect_faces);
  CHECK(stats["defects_cut"]["faces"] == welded.triangles.size());
  CHECK(stats["defects_cut"]["local"] == cut.local);
  CHECK(stats["defects_cut"]["rings"] == -1);
  std::set<std::string> stages;
  for (const nlohmann::json& stage : stats["stages"]) stages.insert(stage["name"]);
  for (const char* name : {"hole_fill_tried", "keep_input_gave_way", "keep_input_abandoned"})
    CHECK(stages.count(name) == 1);
}
