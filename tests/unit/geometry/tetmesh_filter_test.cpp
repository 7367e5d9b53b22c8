// Stage 6: the winding-number filter, and the pipeline frame (options,
// derived parameters, stats, logger).

#include "test_support.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/background_mesh.h>
#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/stats.h>
#include <mr/tetmesh/winding_filter.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace mr;
using namespace mr::tetmesh;

namespace {

TriangleSoup inverted(TriangleSoup soup) {
  for (Triangle& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

BackgroundMesh default_background(const TriangleSoup& soup) {
  const DerivedParameters derived = derive_parameters({}, soup);
  return build_background_mesh(soup, spatial::AabbTree(soup), background_parameters(derived, 0));
}

}  // namespace

TEST_CASE("tetmesh: filter keeps exactly the cube when the background conforms to it", "[tetmesh]") {
  // All lattice points lie farther than 0.51 from the unit cube, hence
  // outside its circumsphere (which bulges 0.37 past a face): the Delaunay
  // tets of the cube corners then tile the cube, whatever the tie-breaking.
  const TriangleSoup cube = test::cube_soup();
  BackgroundParameters parameters;
  parameters.box_min = Vec3d::Constant(-1.0);
  parameters.box_max = Vec3d::Constant(2.0);
  parameters.lattice_spacing = 0.25;
  parameters.lattice_clearance = 0.51;
  const BackgroundMesh background = build_background_mesh(cube, spatial::AabbTree(cube), parameters);
  REQUIRE(background.lattice_points > 0);

  const TetClassification labels =
      classify_tets(background.mesh, WindingNumberTree(cube), WindingRule::positive);
  const TetMesh kept = extract_tets(background.mesh, labels.keep);
  CHECK(labels.kept >= 5);
  CHECK(kept.tets.size() == labels.kept);
  CHECK(kept.positions.size() == 8);
  CHECK(std::abs(test::tet_volume(kept) - 1.0) < 1e-12);
  const check::TetReport report = check::check_tets(kept);
  CHECK(report.valid());
  CHECK(report.boundary.watertight());
  CHECK(std::abs(report.boundary.volume - 1.0) < 1e-12);
}

TEST_CASE("tetmesh: filter labels match the exact winding number at centroids", "[tetmesh]") {
  const TriangleSoup soup = test::cube_soup(0.1, 0.83);
  const BackgroundMesh background = default_background(soup);
  const TetClassification labels =
      classify_tets(background.mesh, WindingNumberTree(soup), WindingRule::positive);
  std::size_t decided = 0, inside = 0;
  for (Index t = 0; t < background.mesh.tet_slots(); ++t) {
    const double exact = winding_number_exact(soup, tet_centroid(background.mesh, t));
    CHECK(std::abs(labels.winding[t] - exact) < 1e-3);
    if (std::abs(exact - 0.5) < 1e-2) continue;  // too close to call for an approximation
    ++decided;
    CHECK((labels.keep[t] != 0) == (exact > 0.5));
    inside += exact > 0.5;
  }
  CHECK(decided > background.mesh.num_tets() * 9 / 10);
  CHECK(inside > 0);
  CHECK(inside < decided);
}

TEST_CASE("tetmesh: the absolute rule keeps inverted solids, the paper's rule does not", "[tetmesh]") {
  const TriangleSoup cube = test::cube_soup();
  const TriangleSoup flipped = inverted(cube);
  const BackgroundMesh background = default_background(cube);
  const auto outward = classify_tets(background.mesh, WindingNumberTree(cube), WindingRule::positive);
  const auto inward_positive =
      classify_tets(background.mesh, WindingNumberTree(flipped), WindingRule::positive);
  const auto inward_absolute =
      classify_tets(background.mesh, WindingNumberTree(flipped), WindingRule::absolute);
  CHECK(outward.kept > 0);
  CHECK(inward_positive.kept == 0);
  CHECK(inward_absolute.keep == outward.keep);
  CHECK(is_inside(-0.6, WindingRule::absolute));
  CHECK_FALSE(is_inside(-0.6, WindingRule::positive));
  CHECK_FALSE(is_inside(0.5, WindingRule::positive));
}

TEST_CASE("tetmesh: extract_tets refuses wrong flags and rational vertices", "[tetmesh]") {
  const BackgroundMesh background = default_background(test::cube_soup());
  CHECK_THROWS_AS(extract_tets(background.mesh, std::vector<char>(3, 1)), UsageError);
  Mesh mesh = background.mesh;
  std::vector<char> keep(mesh.tet_slots(), 0);
  keep[0] = 1;
  CHECK(extract_tets(mesh, keep).tets.size() == 1);
  const Index v = mesh.tet(0)[0];
  mesh.position(v) = HybridPoint::from_exact(ExactPoint3(mpq_class(1, 3), mpq_class(0), mpq_class(0)));
  CHECK_THROWS_AS(extract_tets(mesh, keep), RunError);
  mesh.remove_tet(1);
  keep[1] = 1;
  keep[0] = 0;
  CHECK_THROWS_AS(extract_tets(mesh, keep), UsageError);
}

TEST_CASE("tetmesh: derived parameters follow the paper's defaults", "[tetmesh]") {
  const TriangleSoup cube = test::cube_soup();
  const double b = std::sqrt(3.0);
  const DerivedParameters p = derive_parameters({}, cube);
  CHECK(p.diagonal == Approx(b));
  CHECK(p.epsilon == Approx(b / 1000));
  CHECK(p.edge_length == Approx(b / 20));
  CHECK(p.lattice_spacing == Approx(b / 20));
  CHECK(p.lattice_clearance == Approx(b / 40));
  CHECK(p.box_margin == Approx(b / 20));
  CHECK(p.box_min == Vec3d::Constant(-p.box_margin));

  TetrahedralizeOptions absolute;
  absolute.epsilon_abs = 0.2;
  absolute.edge_length_abs = 0.01;
  absolute.lattice_clearance_rel = 0.2;  // 0.35 > epsilon
  const DerivedParameters q = derive_parameters(absolute, cube);
  CHECK(q.epsilon == 0.2);
  CHECK(q.edge_length == 0.01);
  CHECK(q.box_margin == 0.4);  // 2 epsilon beats a short edge length

  TetrahedralizeOptions bad;
  bad.epsilon_rel = 0.1;  // delta = b/40 < epsilon
  CHECK_THROWS_AS(derive_parameters(bad, cube), UsageError);
  bad = {};
  bad.edge_length_rel = -1;
  CHECK_THROWS_AS(derive_parameters(bad, cube), UsageError);
  bad = {};
  bad.epsilon_rel = std::nan("");
  CHECK_THROWS_AS(derive_parameters(bad, cube), UsageError);
  CHECK_THROWS_AS(derive_parameters({}, TriangleSoup{}), RunError);
  TriangleSoup point;
  point.positions = {Vec3d::Ones(), Vec3d::Ones()};
  CHECK_THROWS_AS(derive_parameters({}, point), RunError);
}

TEST_CASE("tetmesh: stage stats go to JSON and the logger is the caller's", "[tetmesh]") {
  PipelineStats stats;
  std::vector<std::string> messages;
  Logger logger;
  logger.on_message = [&](LogLevel, std::string_view text) { messages.emplace_back(text); };
  {
    StageTimer timer(stats, "background", logger);
    timer.stage().count("tets", 42);
  }
  { StageTimer again(stats, "background", logger); }
  stats.stage("filter").count("kept", 7);
  REQUIRE(stats.stages.size() == 2);
  CHECK(messages.size() == 4);
  CHECK(messages.front() == "start background");

  const nlohmann::json json = nlohmann::json::parse(to_json(stats));
  CHECK(json["stages"][0]["name"] == "background");
  CHECK(json["stages"][0]["counts"]["tets"] == 42);
  CHECK(json["stages"][0]["seconds"].get<double>() >= 0.0);
  CHECK(json["stages"][1]["counts"]["kept"] == 7);
  CHECK(json["total_seconds"].get<double>() == Approx(stats.total_seconds()));
}
