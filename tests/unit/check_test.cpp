#include "test_support.h"

#include <mr/check/distance.h>
#include <mr/check/self_intersections.h>
#include <mr/check/surface_check.h>
#include <mr/check/tet_check.h>

#include <catch2/catch.hpp>

using namespace mr;

namespace {

TriangleSoup two_triangles(const std::vector<Vec3d>& positions, Triangle a, Triangle b) {
  TriangleSoup soup;
  soup.positions = positions;
  soup.triangles = {a, b};
  return soup;
}

}  // namespace

TEST_CASE("a closed cube is watertight", "[check]") {
  const check::SurfaceReport report = check::check_surface(test::cube_soup());
  CHECK(report.vertices == 8);
  CHECK(report.faces == 12);
  CHECK(report.closed());
  CHECK(report.manifold());
  CHECK(report.inconsistent_edges == 0);
  CHECK(report.self_intersecting_pairs == 0);
  CHECK(report.components == 1);
  CHECK(report.volume == Approx(1.0));
  CHECK(report.watertight());
}

TEST_CASE("the enclosed volume has the right sign on a sliver reaching far away", "[check]") {
  // A tet with one corner 1e25 away: about its box's centre the six-fold
  // volume is a sum of terms near 1e74 that cancel to 1e25, and rounds to 0.
  TriangleSoup tet;
  tet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1e25, 1e25, 1e25}};
  tet.triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  const check::SurfaceReport outward = check::check_surface(tet);
  CHECK(outward.volume == Approx(1e25 / 6));
  CHECK(outward.watertight());
  for (Triangle& t : tet.triangles) std::swap(t[1], t[2]);
  CHECK(check::check_surface(tet).volume == Approx(-1e25 / 6));
}

TEST_CASE("surface defects are counted", "[check]") {
  TriangleSoup open = test::cube_soup();
  open.triangles.pop_back();
  CHECK(check::check_surface(open).boundary_edges == 3);

  TriangleSoup flipped = test::cube_soup();
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  CHECK(check::check_surface(flipped).inconsistent_edges == 3);
  CHECK_FALSE(check::check_surface(flipped).watertight());

  TriangleSoup inverted = test::cube_soup();
  for (Triangle& t : inverted.triangles) std::swap(t[1], t[2]);
  CHECK(check::check_surface(inverted).volume == Approx(-1.0));
  CHECK_FALSE(check::check_surface(inverted).watertight());

  const check::SurfaceReport soup = check::check_surface(test::non_manifold_soup());
  CHECK(soup.nonmanifold_edges == 1);
  CHECK(soup.duplicate_faces == 1);
  CHECK(soup.degenerate_faces == 2);  // the zero-area face and the repeated index

  // Two cubes touching at one corner: a non-manifold vertex, two components? No:
  // they share the corner vertex, so one component with a pinched vertex.
  TriangleSoup pinched = test::cube_soup();
  pinched.append(test::cube_soup(1, 2));
  const check::SurfaceReport pinch = check::check_surface(pinched);
  CHECK(pinch.nonmanifold_vertices == 1);
  CHECK(pinch.components == 1);
  CHECK(pinch.self_intersecting_pairs == 0);
}

TEST_CASE("self-intersections are decided exactly in every contact case", "[check]") {
  const std::vector<Vec3d> p = {{0, 0, 0},  {2, 0, 0},      {0, 2, 0},    {1, 1, 0},
                                {1, -1, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}};
  // Sharing edge 0-1, folded onto each other in the plane: intersect.
  CHECK(check::count_self_intersections(two_triangles(p, {0, 1, 2}, {0, 1, 3})) == 1);
  // Sharing edge 0-1, on opposite sides: meet only along the edge.
  CHECK(check::count_self_intersections(two_triangles(p, {0, 1, 2}, {1, 0, 4})) == 0);
  // Sharing vertex 0, coplanar, the second inside the first's angle: overlap.
  const std::vector<Vec3d> q = {{0, 0, 0},   {4, 0, 0},     {0, 4, 0},    {1, 0.5, 0},
                                {0.5, 1, 0}, {-1, -0.5, 0}, {-0.5, -1, 0}};
  CHECK(check::count_self_intersections(two_triangles(q, {0, 1, 2}, {0, 3, 4})) == 1);
  // Sharing vertex 0, coplanar, pointing away: only the vertex.
  CHECK(check::count_self_intersections(two_triangles(q, {0, 1, 2}, {0, 5, 6})) == 0);
  // Sharing vertex 0, the second piercing the first's plane through its interior.
  const std::vector<Vec3d> r = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -1}, {1, 1, 1}};
  CHECK(check::count_self_intersections(two_triangles(r, {0, 1, 2}, {0, 3, 4})) == 1);
  // Disjoint, and touching at one point (vertex on a face interior).
  const std::vector<Vec3d> s = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0},  {1, 1, 0},
                                {1, 1, 1}, {2, 1, 1}, {1, 1, 0.5}};
  CHECK(check::count_self_intersections(two_triangles(s, {0, 1, 2}, {3, 4, 5})) == 1);
  CHECK(check::count_self_intersections(two_triangles(s, {0, 1, 2}, {6, 4, 5})) == 0);
  // A duplicate face.
  CHECK(check::count_self_intersections(two_triangles(p, {0, 1, 2}, {2, 1, 0})) == 1);
  // Overlapping cubes.
  TriangleSoup cubes = test::cube_soup(0, 2);
  cubes.append(test::cube_soup(1, 3));
  CHECK(check::count_self_intersections(cubes) > 0);
}

TEST_CASE("tet checks: exact orientation and quality", "[check]") {
  const check::TetReport report = check::check_tets(test::cube_tets());
  CHECK(report.valid());
  CHECK(report.volume == Approx(1.0));
  CHECK(report.boundary.watertight());
  CHECK(report.min_dihedral_deg > 0);

  TetMesh inverted = test::cube_tets();
  std::swap(inverted.tets[2][0], inverted.tets[2][1]);
  CHECK(check::check_tets(inverted).inverted_tets == 1);

  TetMesh flat = test::cube_tets();
  flat.positions.push_back({0.5, 0.5, 0.0});
  flat.tets.push_back({0, 1, 2, 8});  // four coplanar points
  CHECK(check::check_tets(flat).degenerate_tets == 1);

  const Vec3d a(1, 0, -1 / std::sqrt(2.0)), b(-1, 0, -1 / std::sqrt(2.0)), c(0, 1, 1 / std::sqrt(2.0)),
      d(0, -1, 1 / std::sqrt(2.0));
  const bool positive = (b - a).cross(c - a).dot(d - a) > 0;
  CHECK(check::amips_energy(a, b, positive ? c : d, positive ? d : c) == Approx(3.0));
  CHECK(check::min_dihedral_angle_deg(a, b, c, d) == Approx(std::acos(1.0 / 3) * 180 / M_PI));
}

TEST_CASE("AMIPS is infinite only for a tet flat or inverted exactly", "[check]") {
  // The fourth corner walks across the plane of the other three one double
  // at a time: there the determinant of the rounded edges is rounding error
  // of either sign, and only the exact sign may decide.
  const Vec3d a(0.1, 0.2, 0.3), b(1.7, 0.4, 0.35), c(0.3, 1.9, 0.33);
  const Vec3d normal = (b - a).cross(c - a);
  const double x = 0.9, y = 0.8;
  double z = a.z() - (normal.x() * (x - a.x()) + normal.y() * (y - a.y())) / normal.z();
  const double down = -std::numeric_limits<double>::infinity(), up = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 40; ++i) z = std::nextafter(z, down);
  int positive = 0, flat_or_inverted = 0;
  double largest_finite = 0;
  for (int i = 0; i < 80; ++i, z = std::nextafter(z, up)) {
    const Vec3d d(x, y, z);
    TetMesh tet;
    tet.positions = {a, b, c, d};
    tet.tets = {{0, 1, 2, 3}};
    const check::TetReport report = check::check_tets(tet);
    const double energy = check::amips_energy(a, b, c, d);
    if (report.inverted_tets == 0 && report.degenerate_tets == 0) {
      ++positive;
      REQUIRE(std::isfinite(energy));
      largest_finite = std::max(largest_finite, energy);
    } else {
      ++flat_or_inverted;
      REQUIRE(std::isinf(energy));
    }
  }
  CHECK(positive > 10);
  CHECK(flat_or_inverted > 10);
  // A tet positive exactly whose rounded determinant is negative (-1.4e-17).
  const Vec3d p(-0.41627067894555503, -0.50044415316658108, -0.16266294128208603),
      q(-0.46012099168103904, -0.05081238862887294, 0.6064726443345807),
      r(-0.083750897556795323, 0.49798156300998464, -0.42791636929363763),
      s(-0.39584124366371942, -0.55176571332392588, -0.32124883905992208);
  TetMesh sliver;
  sliver.positions = {p, q, r, s};
  sliver.tets = {{0, 1, 2, 3}};
  REQUIRE(check::check_tets(sliver).valid());
  CHECK(std::isfinite(check::amips_energy(p, q, r, s)));
  CHECK(largest_finite > 1e8);  // the exact path was taken
  // Where the rounded determinant is sound, both paths agree: near flat
  // the energy grows as height^(-2/3).
  const Vec3d foot = (a + b + c) / 3, unit_normal = normal.normalized();
  const double near = check::amips_energy(a, b, c, foot + 1e-6 * unit_normal);     // about 1e4: rounded path
  const double nearer = check::amips_energy(a, b, c, foot + 1e-12 * unit_normal);  // about 1e8: exact path
  CHECK(nearer > 1e8);
  CHECK(nearer / near == Approx(1e4).epsilon(1e-3));
}

TEST_CASE("sampled distance between surfaces", "[check][slow]") {
  const TriangleSoup cube = test::cube_soup();
  CHECK(check::one_sided_distance(cube, cube).max == Approx(0.0).margin(1e-12));
  const TriangleSoup bigger = test::cube_soup(-0.1, 1.1);
  const check::DistanceReport report = check::one_sided_distance(bigger, cube);
  CHECK(report.max == Approx(std::sqrt(3 * 0.01)).epsilon(1e-9));  // the corners
  CHECK(report.samples > 1000);
  // The farthest sample is reported: one of the bigger cube's corners.
  for (int k = 0; k < 3; ++k) CHECK(std::abs(report.farthest[k] - 0.5) == Approx(0.6));
}

TEST_CASE("sampled distance: points on a sliver 1e25 long are on it", "[check]") {
  TriangleSoup sheets;  // the meshrepair fuzzer's unit triangle and sliver
  sheets.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1e25, 1e25, 1e25}};
  sheets.triangles = {{0, 1, 2}, {0, 1, 3}};
  TriangleSoup part;  // a triangle inside the sliver, sharing none of its faces
  part.positions = {{0, 0, 0}, {0.5, 0, 0}, {5e24, 5e24, 5e24}};
  part.triangles = {{0, 1, 2}};
  CHECK(check::one_sided_distance(part, sheets).max <= 1e-9 * 1e25);
}

TEST_CASE("sampled distance: a face of the other surface is at 0, a face moved off it is not", "[check]") {
  const TriangleSoup cube = test::cube_soup();
  // The same faces with their corners renumbered and each face's corners rotated.
  TriangleSoup renumbered;
  renumbered.positions.assign(cube.positions.rbegin(), cube.positions.rend());
  const auto last = static_cast<Index>(cube.positions.size() - 1);
  for (const Triangle& t : cube.triangles)
    renumbered.triangles.push_back({last - t[1], last - t[2], last - t[0]});
  const check::DistanceReport same = check::one_sided_distance(renumbered, cube);
  CHECK(same.max == 0.0);
  CHECK(same.mean == 0.0);
  // One corner of one face moved out by 0.25: that face's samples are measured, the rest are 0.
  TriangleSoup moved = cube;
  moved.positions.push_back(moved.positions[moved.triangles[0][0]] + Vec3d(0, 0, -0.25));
  moved.triangles[0][0] = static_cast<Index>(moved.positions.size() - 1);
  const check::DistanceReport off = check::one_sided_distance(moved, cube);
  CHECK(off.max == Approx(0.25).epsilon(1e-9));
  CHECK(off.mean > 0.0);
}

TEST_CASE("lies within: every sample within the distance, as one_sided_distance measures it", "[check]") {
  const TriangleSoup cube = test::cube_soup();
  CHECK(check::lies_within(cube, cube, 0.0));  // every face is a face of the other
  const TriangleSoup bigger = test::cube_soup(-0.1, 1.1);
  CHECK(check::lies_within(bigger, cube, 0.18));  // its corners are sqrt(0.03) = 0.173 away
  CHECK_FALSE(check::lies_within(bigger, cube, 0.17));
  // A triangle through the cube between three of its corners on no common
  // face: its corners are on the cube, its middle is not.
  TriangleSoup across;
  across.positions = {{0, 0, 0}, {1, 1, 0}, {0, 1, 1}};
  across.triangles = {{0, 1, 2}};
  const double farthest = check::one_sided_distance(across, cube).max;
  REQUIRE(farthest > 0.2);
  CHECK(check::lies_within(across, cube, 1.01 * farthest));
  CHECK_FALSE(check::lies_within(across, cube, 0.99 * farthest));
  CHECK_FALSE(check::lies_within(cube, TriangleSoup{}, 1.0));
  CHECK(check::lies_within(TriangleSoup{}, cube, 0.0));
}
