// Coherent orientation of soups: flipped faces are turned back, whole
// shells keep the orientation of the larger part, unwelded copies of a
// vertex count as one, and caller-given votes decide a patch's side.

#include "test_support.h"

#include <mr/core/double_sided.h>
#include <mr/core/orientation.h>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace mr;

namespace {

void flip(TriangleSoup& soup, std::size_t face) {
  std::swap(soup.triangles[face][1], soup.triangles[face][2]);
}

// Every vertex its own copy, as an STL reader that does not weld gives.
TriangleSoup unwelded(const TriangleSoup& soup) {
  TriangleSoup out;
  for (const Triangle& t : soup.triangles) {
    const Index base = static_cast<Index>(out.positions.size());
    for (const Index v : t) out.positions.push_back(soup.positions[v]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

}  // namespace

TEST_CASE("orientation: a flipped face of a cube is turned back", "[orientation]") {
  TriangleSoup soup = test::cube_soup();
  flip(soup, 3);
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.patches == 1);
  CHECK(stats.flipped == 1);
  CHECK(stats.conflicts == 0);
  CHECK(soup.triangles == test::cube_soup().triangles);
  CHECK(test::enclosed_volume(soup) == Approx(1.0));
}

TEST_CASE("orientation: the larger part of a patch keeps its orientation", "[orientation]") {
  TriangleSoup soup = test::cube_soup();
  for (std::size_t f = 0; f < 8; ++f) flip(soup, f);  // 8 of 12 faces inward
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.flipped == 4);
  CHECK(test::enclosed_volume(soup) == Approx(-1.0));
}

TEST_CASE("orientation: an inward shell is a patch of its own and stays inward", "[orientation]") {
  TriangleSoup soup = test::cube_soup(0.0, 3.0);
  TriangleSoup cavity = test::cube_soup(1.0, 2.0);
  for (std::size_t f = 0; f < cavity.triangles.size(); ++f) flip(cavity, f);
  soup.append(cavity);
  const TriangleSoup before = soup;
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.patches == 2);
  CHECK(stats.flipped == 0);
  CHECK(soup.triangles == before.triangles);
}

TEST_CASE("orientation: vertices are matched by position, not by index", "[orientation]") {
  TriangleSoup soup = unwelded(test::cube_soup());
  flip(soup, 5);
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.patches == 1);
  CHECK(stats.flipped == 1);
  CHECK(test::enclosed_volume(soup) == Approx(1.0));
}

TEST_CASE("orientation: non-manifold edges split patches and are left alone", "[orientation]") {
  TriangleSoup soup = test::non_manifold_soup();
  const TriangleSoup before = soup;
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.flipped == 0);
  CHECK(soup.triangles == before.triangles);
}

TEST_CASE("orientation: votes decide which side a patch keeps", "[orientation]") {
  TriangleSoup soup = test::cube_soup();
  flip(soup, 0);
  std::vector<double> votes(soup.triangles.size(), -0.1);
  votes[0] = 5.0;  // only the flipped face is sure of itself
  const OrientationStats stats = orient_coherently(soup, votes);
  CHECK(stats.flipped == 11);
  CHECK(test::enclosed_volume(soup) == Approx(-1.0));
  CHECK_THROWS(orient_coherently(soup, std::vector<double>(3, 1.0)));
}

TEST_CASE("orientation: a Moebius strip reports its conflict", "[orientation]") {
  // A strip of 6 triangles closed with a half twist cannot be oriented.
  TriangleSoup soup;
  constexpr int kSegments = 3;
  for (int i = 0; i < kSegments; ++i) {
    const double angle = 2.0 * 3.14159265358979 * i / kSegments;
    const double twist = 0.5 * angle;
    const Vec3d centre(3.0 * std::cos(angle), 3.0 * std::sin(angle), 0.0);
    const Vec3d radial(std::cos(angle), std::sin(angle), 0.0);
    const Vec3d across = std::cos(twist) * radial + std::sin(twist) * Vec3d::UnitZ();
    soup.positions.push_back(centre + across);
    soup.positions.push_back(centre - across);
  }
  for (Index i = 0; i < kSegments; ++i) {
    const Index a = 2 * i, b = 2 * i + 1;
    // The last segment joins top to bottom: the half twist.
    const bool last = i + 1 == kSegments;
    const Index c = last ? 1 : 2 * i + 2, d = last ? 0 : 2 * i + 3;
    soup.triangles.push_back({a, b, c});
    soup.triangles.push_back({b, d, c});
  }
  const OrientationStats stats = orient_coherently(soup);
  CHECK(stats.patches == 1);
  CHECK(stats.conflicts >= 1);
}

// Every face of a cube twice, in both orientations, the copy first on half
// of them (as double-sided exports write them): its winding number is 0
// everywhere until one copy of each face is dropped and the cube is turned
// outward.
TEST_CASE("double-sided: a cube written double-sided becomes one outward cube", "[orientation]") {
  const TriangleSoup cube = test::cube_soup();
  TriangleSoup soup;
  soup.positions = cube.positions;
  for (std::size_t f = 0; f < cube.triangles.size(); ++f) {
    Triangle t = cube.triangles[f];
    Triangle r{t[0], t[2], t[1]};
    if (f % 2 == 0) std::swap(t, r);
    soup.triangles.push_back(t);
    soup.triangles.push_back(r);
  }
  CHECK(test::enclosed_volume(soup) == Approx(0.0).margin(1e-12));
  CHECK(make_double_sided_components_one_sided(soup) == 12);
  REQUIRE(soup.triangles.size() == 12);
  CHECK(test::enclosed_volume(soup) == Approx(1.0));
}

// Two tets glued along a face written once each way: that face is a wall
// between parts and must still cancel.
TEST_CASE("double-sided: a shared wall between two parts is left alone", "[orientation]") {
  TriangleSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}};
  soup.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2},   // upper tet, the wall {0, 2, 1} facing down
                    {0, 1, 2}, {0, 4, 1}, {1, 4, 2}, {0, 2, 4}};  // lower tet, the wall facing up
  const TriangleSoup before = soup;
  CHECK(make_double_sided_components_one_sided(soup) == 0);
  CHECK(soup.triangles == before.triangles);
}

// An open sheet written double-sided is a wall of no thickness: it stays
// as it is (the pipeline thickens it).
TEST_CASE("double-sided: an open double-sided sheet is left alone", "[orientation]") {
  TriangleSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  soup.triangles = {{0, 1, 2}, {0, 2, 1}, {0, 2, 3}, {0, 3, 2}};
  const TriangleSoup before = soup;
  CHECK(make_double_sided_components_one_sided(soup) == 0);
  CHECK(soup.triangles == before.triangles);
}

// Faces stored twice the same way round (soups, careless exporters): the
// copies go, whatever the corner order and even on unwelded corners; copies
// the other way round stay.
TEST_CASE("repeated faces: same-way copies are dropped, opposite copies kept", "[orientation]") {
  TriangleSoup soup = test::cube_soup();
  soup.face_regions.assign(soup.triangles.size(), 0);
  const Triangle first = soup.triangles[0], second = soup.triangles[1];
  soup.triangles.push_back({first[1], first[2], first[0]});  // the same face, rotated
  soup.face_regions.push_back(7);
  // The same face again on its own (unwelded) corners.
  const auto corner = static_cast<Index>(soup.positions.size());
  for (Index v : second) soup.positions.push_back(soup.positions[v]);
  soup.triangles.push_back({corner, corner + 1, corner + 2});
  soup.face_regions.push_back(8);
  soup.triangles.push_back({second[0], second[2], second[1]});  // reversed: kept
  soup.face_regions.push_back(9);
  CHECK(drop_repeated_faces(soup) == 2);
  REQUIRE(soup.triangles.size() == 13);
  CHECK(soup.triangles.back() == Triangle{second[0], second[2], second[1]});
  CHECK(soup.face_regions.back() == 9);
  CHECK(soup.face_regions.size() == 13);
}
