// Stage 4: exact triangle insertion. After inserting a soup, the mesh must
// satisfy every invariant (find_mesh_inconsistency: exact orientation,
// conforming adjacency, two-sided marks) and each input triangle must be
// exactly covered by the faces marked with its id: their areas add up to
// the triangle's area (up to the rounding of cut points to doubles). Where
// coplanar neighbours were inserted as one polygon, the faces marked with
// the polygon's id add up to the area of all its triangles.

#include "mesh_generators.h"
#include "test_support.h"

#include <mr/kernel/predicates.h>
#include <mr/tetmesh/background_mesh.h>
#include <mr/tetmesh/insertion.h>
#include <mr/tetmesh/mesh_check.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <random>

using namespace mr;
using namespace mr::tetmesh;

namespace {

double triangle_area(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

// Area of the faces carrying each id, each face counted once.
std::map<std::uint32_t, double> marked_area(const Mesh& mesh) {
  std::map<std::uint32_t, double> area;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.neighbour(t, k);
      if (!mesh.is_surface_face(t, k) || (n != kNoTet && n < t)) continue;
      const auto f = mesh.face_vertices(t, k);
      const double a =
          triangle_area(mesh.position(f[0]).approx, mesh.position(f[1]).approx, mesh.position(f[2]).approx);
      for (std::uint32_t id : mesh.surface_ids(t, k)) area[id] += a;
    }
  }
  return area;
}

struct Inserted {
  BackgroundMesh background;
  InsertionStats stats;
};

Inserted insert_soup(const TriangleSoup& soup, const InsertionOptions& options = {}) {
  const DerivedParameters derived = derive_parameters({}, soup);
  Inserted result{build_background_mesh(soup, spatial::AabbTree(soup), background_parameters(derived, 1)),
                  {}};
  result.stats =
      insert_triangles(result.background.mesh, soup, result.background.input_vertex, {}, {}, options);
  return result;
}

void require_exactly_embedded(const TriangleSoup& soup, const Inserted& inserted) {
  const Mesh& mesh = inserted.background.mesh;
  REQUIRE(find_mesh_inconsistency(mesh) == "");
  const std::map<std::uint32_t, double> area = marked_area(mesh);
  const std::vector<std::uint32_t>& marked_as = inserted.stats.marked_as;
  REQUIRE(marked_as.size() == soup.triangles.size());
  std::map<std::uint32_t, double> expected_area;
  for (std::size_t i = 0; i < soup.triangles.size(); ++i) {
    const Triangle& f = soup.triangles[i];
    expected_area[static_cast<std::uint32_t>(i)] += 0.0;  // every id is checked, merged ones against 0
    expected_area[marked_as[i]] +=
        triangle_area(soup.positions[f[0]], soup.positions[f[1]], soup.positions[f[2]]);
  }
  // Until the rounding stage, a tracked face lies exactly in the plane of
  // every triangle it is marked with (a cut point rounded early would take
  // its faces off the plane, and later coplanar triangles would miss them).
  std::size_t off_plane = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int k = 0; k < 4; ++k) {
      for (const std::uint32_t id : mesh.surface_ids(t, k)) {
        const Triangle& f = soup.triangles[id];
        for (const Index v : mesh.face_vertices(t, k)) {
          off_plane += orient3d(HybridPoint(soup.positions[f[0]]), HybridPoint(soup.positions[f[1]]),
                                HybridPoint(soup.positions[f[2]]), mesh.position(v)) != 0;
        }
      }
    }
  }
  CHECK(off_plane == 0);
  for (const auto& [id, expected] : expected_area) {
    const auto it = area.find(id);
    const double got = it == area.end() ? 0.0 : it->second;
    INFO("id " << id << " got " << got << " expected " << expected);
    CHECK(std::abs(got - expected) <= 1e-9 * std::max(1.0, expected));
  }
}

TriangleSoup random_soup(unsigned seed, int triangles) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(0.0, 1.0);
  TriangleSoup soup;
  for (int i = 0; i < 3 * triangles; ++i) {
    soup.positions.emplace_back(coordinate(random), coordinate(random), coordinate(random));
  }
  for (int i = 0; i < triangles; ++i) {
    soup.triangles.push_back({Index(3 * i), Index(3 * i + 1), Index(3 * i + 2)});
  }
  return soup;
}

TriangleSoup merged(const TriangleSoup& a, const TriangleSoup& b) {
  TriangleSoup soup = a;
  const Index offset = static_cast<Index>(a.positions.size());
  soup.positions.insert(soup.positions.end(), b.positions.begin(), b.positions.end());
  for (Triangle f : b.triangles) soup.triangles.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return soup;
}

}  // namespace

TEST_CASE("insertion: a cube's faces become mesh faces", "[tetmesh][insertion]") {
  const TriangleSoup cube = test::cube_soup();
  SECTION("each triangle on its own") {
    InsertionOptions options;
    options.merge_coplanar = false;
    const Inserted inserted = insert_soup(cube, options);
    CHECK(inserted.stats.inserted == 12);
    CHECK(inserted.stats.merged == 0);
    require_exactly_embedded(cube, inserted);
  }
  SECTION("the two triangles of each side as one square") {
    const Inserted inserted = insert_soup(cube);
    CHECK(inserted.stats.inserted == 6);
    CHECK(inserted.stats.polygons == 6);
    CHECK(inserted.stats.merged == 6);
    require_exactly_embedded(cube, inserted);
  }
}

TEST_CASE("insertion: triangles that are mesh faces already are marked without a cut",
          "[tetmesh][insertion]") {
  // The background is the Delaunay mesh of the sphere's vertices, and a
  // fine sphere's triangles are nearly all Delaunay faces.
  const TriangleSoup sphere = test::sphere(1.0, 3);
  const Inserted inserted = insert_soup(sphere);
  CAPTURE(inserted.stats.already_faces, inserted.stats.new_vertices);
  CHECK(inserted.stats.inserted == sphere.triangles.size());
  CHECK(inserted.stats.already_faces > sphere.triangles.size() / 2);
  CHECK(inserted.stats.already_faces <= inserted.stats.inserted);
  require_exactly_embedded(sphere, inserted);
}

TEST_CASE("insertion: two overlapping cubes cut each other", "[tetmesh][insertion]") {
  const TriangleSoup soup = merged(test::cube_soup(0.0, 1.0), test::cube_soup(0.5, 1.5));
  const Inserted inserted = insert_soup(soup);
  CHECK(inserted.stats.new_vertices > 0);
  require_exactly_embedded(soup, inserted);
}

TEST_CASE("insertion: coplanar overlapping and duplicated triangles", "[tetmesh][insertion]") {
  TriangleSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 0}, {1.3, 0.4, 0}, {0.1, 0.9, 0}, {0, 0, 1}};
  soup.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 1, 2}, {2, 1, 0}, {0, 1, 6}};
  const Inserted inserted = insert_soup(soup);
  CHECK(inserted.stats.copies == 2);  // inserted once, marked three times
  CHECK(inserted.stats.inserted == 3);
  require_exactly_embedded(soup, inserted);
}

TEST_CASE("insertion: degenerate triangles are skipped, the rest embedded", "[tetmesh][insertion]") {
  TriangleSoup soup = test::cube_soup();
  const Index base = static_cast<Index>(soup.positions.size());
  soup.positions.push_back({0.25, 0.5, 0.75});  // three exactly collinear points
  soup.positions.push_back({0.5, 1.0, 1.5});
  soup.positions.push_back({0.75, 1.5, 2.25});
  soup.triangles.push_back({base, base + 1, base + 2});
  soup.triangles.push_back({base, base, base + 1});
  const Inserted inserted = insert_soup(soup);
  CHECK(inserted.stats.degenerate == 2);
  CHECK(find_mesh_inconsistency(inserted.background.mesh) == "");
}

TEST_CASE("insertion: random intersecting soups are embedded exactly", "[tetmesh][insertion][slow]") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const TriangleSoup soup = random_soup(seed, 25);
    INFO("seed " << seed);
    const Inserted inserted = insert_soup(soup);
    require_exactly_embedded(soup, inserted);
  }
}

TEST_CASE("insertion: in random order the embedding is exact and the same every run",
          "[tetmesh][insertion][slow]") {
  const TriangleSoup soup = random_soup(4, 25);
  InsertionOptions options;
  options.random_order = true;
  const Inserted first = insert_soup(soup, options);
  require_exactly_embedded(soup, first);
  const Inserted again = insert_soup(soup, options);
  CHECK(again.stats.new_vertices == first.stats.new_vertices);
  REQUIRE(again.background.mesh.tet_slots() == first.background.mesh.tet_slots());
  for (Index t = 0; t < first.background.mesh.tet_slots(); ++t) {
    REQUIRE(again.background.mesh.tet_alive(t) == first.background.mesh.tet_alive(t));
    if (first.background.mesh.tet_alive(t))
      REQUIRE(again.background.mesh.tet(t) == first.background.mesh.tet(t));
  }
  // The order differs from the input's: file order cuts another mesh.
  const Inserted in_order = insert_soup(soup);
  require_exactly_embedded(soup, in_order);
  CHECK(in_order.stats.new_vertices != first.stats.new_vertices);
}

TEST_CASE("insertion: cut points near a later plane move onto it, the embedding still exact",
          "[tetmesh][insertion]") {
  // A unit cube whose top is two triangles all but coplanar (one corner
  // raised by 1e-9): the first one's plane cuts the tets beyond its
  // diagonal within 1e-9 of the second one's plane.
  TriangleSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},        {0, 1, 0},
                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1 + 1e-9}, {0, 1, 1}};
  soup.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                    {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  // Settling would collapse those points away before the second triangle
  // comes: off here, to see the snap alone.
  InsertionOptions plain_options;
  plain_options.settle_cut_points = false;
  const Inserted plain = insert_soup(soup, plain_options);
  require_exactly_embedded(soup, plain);
  CHECK(plain.stats.snapped_points == 0);
  InsertionOptions snapping = plain_options;
  snapping.snap_distance = derive_parameters({}, soup).snap_spacing;
  REQUIRE(snapping.snap_distance > 0);
  const Inserted snapped = insert_soup(soup, snapping);
  require_exactly_embedded(soup, snapped);
  CHECK(snapped.stats.snapped_points > 0);
  CHECK(snapped.stats.new_vertices < plain.stats.new_vertices);
}

TEST_CASE("insertion: cut points that grow too long are rounded at once, the embedding still exact",
          "[tetmesh][insertion][slow]") {
  // Many triangles through one region: cuts of cuts of cuts, whose exact
  // coordinates grow past a bound set low enough for a small soup.
  const TriangleSoup soup = random_soup(7, 30);
  InsertionOptions options;
  options.max_exact_bits = 1024;
  const Inserted inserted = insert_soup(soup, options);
  INFO("rounded during insertion: " << inserted.stats.eagerly_rounded << " of " << inserted.stats.new_vertices
                                    << " rational left " << inserted.stats.rational_vertices);
  CHECK(inserted.stats.eagerly_rounded > 0);
  require_exactly_embedded(soup, inserted);
}

namespace {

// A planar fan: triangles (0, i, i + 1) over `corners` points of a circle in
// the plane z = 0.5 (exact coordinates on a dyadic grid), with the given
// orientation of each triangle.
TriangleSoup planar_fan(const std::vector<Vec3d>& rim, const std::vector<bool>& reversed) {
  TriangleSoup soup;
  soup.positions = rim;
  for (Index i = 1; i + 1 < static_cast<Index>(rim.size()); ++i) {
    if (reversed[i - 1]) {
      soup.triangles.push_back({0, i + 1, i});
    } else {
      soup.triangles.push_back({0, i, i + 1});
    }
  }
  return soup;
}

std::vector<Vec3d> octagon() {
  return {{0.5, 0.0, 0.5}, {0.85, 0.15, 0.5}, {1.0, 0.5, 0.5}, {0.85, 0.85, 0.5},
          {0.5, 1.0, 0.5}, {0.15, 0.85, 0.5}, {0.0, 0.5, 0.5}, {0.15, 0.15, 0.5}};
}

}  // namespace

TEST_CASE("insertion: a fan of coplanar triangles is one convex polygon, cut along its rim only",
          "[tetmesh][insertion]") {
  const TriangleSoup fan = planar_fan(octagon(), std::vector<bool>(6, false));
  InsertionOptions separate;
  separate.merge_coplanar = false;
  const Inserted alone = insert_soup(fan, separate);
  const Inserted merged_fan = insert_soup(fan);
  CHECK(merged_fan.stats.inserted == 1);
  CHECK(merged_fan.stats.polygons == 1);
  CHECK(merged_fan.stats.merged == 5);
  for (std::uint32_t id : merged_fan.stats.marked_as) CHECK(id == 0);
  require_exactly_embedded(fan, merged_fan);
  require_exactly_embedded(fan, alone);
  // The diagonals from corner 0 are no longer cut into the mesh.
  INFO("cut points: merged " << merged_fan.stats.new_vertices << ", separate " << alone.stats.new_vertices);
  CHECK(merged_fan.stats.new_vertices < alone.stats.new_vertices);
}

TEST_CASE("insertion: coplanar triangles merge only where the polygon stays convex and oriented alike",
          "[tetmesh][insertion]") {
  SECTION("a flipped triangle in the fan splits it") {
    std::vector<bool> reversed(6, false);
    reversed[2] = true;
    const TriangleSoup fan = planar_fan(octagon(), reversed);
    const Inserted inserted = insert_soup(fan);
    CHECK(inserted.stats.marked_as[2] == 2);  // alone: opposite orientation
    CHECK(inserted.stats.marked_as[1] != inserted.stats.marked_as[3]);
    require_exactly_embedded(fan, inserted);
  }
  SECTION("a non-convex fan is cut into convex polygons") {
    std::vector<Vec3d> rim = octagon();
    rim[4] = {0.5, 0.3, 0.5};  // a reflex corner
    const TriangleSoup fan = planar_fan(rim, std::vector<bool>(6, false));
    const Inserted inserted = insert_soup(fan);
    CHECK(inserted.stats.merged > 0);
    CHECK(inserted.stats.marked_as[2] != inserted.stats.marked_as[3]);  // their union has the reflex corner
    require_exactly_embedded(fan, inserted);
  }
  SECTION("a triangle folded back over its neighbour stays apart") {
    // (0, 2, 3) runs like (0, 1, 2) by its indices, but its corner 3 lies
    // inside (0, 1, 2): the fold overlaps it with the opposite orientation.
    TriangleSoup soup;
    soup.positions = {{0, 0, 0.5}, {0, 1, 0.5}, {1, 1, 0.5}, {0.45, 0.55, 0.5}};
    soup.triangles = {{0, 1, 2}, {0, 2, 3}};
    const Inserted inserted = insert_soup(soup);
    CHECK(inserted.stats.merged == 0);
    require_exactly_embedded(soup, inserted);
  }
  SECTION("triangles sharing an edge in different planes stay apart") {
    TriangleSoup soup;
    soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 1e-9}};
    soup.triangles = {{0, 1, 2}, {2, 1, 3}};
    const Inserted inserted = insert_soup(soup);
    CHECK(inserted.stats.merged == 0);
    require_exactly_embedded(soup, inserted);
  }
}

namespace {

// `pages` parallel pages in 9 piles, stacked through the unit height: each
// cuts about as many tets as the one before, so the growth of the first
// ones tells where the run is going.
TriangleSoup stacked_pages(int pages) {
  TriangleSoup book;
  for (int i = 0; i < pages; ++i) {
    const double x = 0.35 * (i % 3), y = 0.35 * ((i / 3) % 3), z = double(i) / pages;
    const auto first = static_cast<Index>(book.positions.size());
    book.positions.insert(book.positions.end(), {{x, y, z}, {x + 0.3, y, z}, {x, y + 0.3, z}});
    book.triangles.push_back({first, Index(first + 1), Index(first + 2)});
  }
  return book;
}

// Inserts `book` into its background mesh under a budget of three times
// the background's tets, without settling cut points: each page then cuts
// every sliver the pages before it left, the growth the budget is for.
struct BudgetRun {
  std::string stopped;  ///< InsertionTooCostly's message, empty if it ran to the end
  std::size_t tets = 0, max_tets = 0;
};

BudgetRun insert_under_budget(const TriangleSoup& book) {
  const DerivedParameters derived = derive_parameters({}, book);
  BackgroundMesh background =
      build_background_mesh(book, spatial::AabbTree(book), background_parameters(derived, 1));
  InsertionOptions options;
  options.settle_cut_points = false;
  options.max_tets = 3 * background.mesh.num_tets();
  BudgetRun run;
  run.max_tets = options.max_tets;
  try {
    insert_triangles(background.mesh, book, background.input_vertex, {}, {}, options);
  } catch (const InsertionTooCostly& e) {
    run.stopped = e.what();
  }
  run.tets = background.mesh.num_tets();
  return run;
}

}  // namespace

TEST_CASE("insertion: a run on course for four times its tet budget stops early", "[tetmesh][insertion]") {
  const BudgetRun run = insert_under_budget(stacked_pages(1000));
  INFO(run.stopped);
  const std::size_t tets_at_stop = run.stopped.empty() ? 0 : run.tets;
  if (!run.stopped.empty()) CHECK(run.stopped.find("on course for") != std::string::npos);
  CHECK(tets_at_stop > 0);
  CHECK(tets_at_stop <= run.max_tets);
}

TEST_CASE("insertion: a run on course for 32 times its tet budget stops after its first 8 triangles",
          "[tetmesh][insertion]") {
  // 4 times as dense as above: each of the first pages cuts thousands of
  // tets, so 8 tell that the run would end far past the budget, long
  // before the 32 the milder projection waits for.
  const BudgetRun run = insert_under_budget(stacked_pages(4000));
  INFO(run.stopped);
  CHECK(run.stopped.find("more than 32 times its budget") != std::string::npos);
  const std::size_t after = run.stopped.find(" tets after ");
  REQUIRE(after != std::string::npos);
  const int done = std::stoi(run.stopped.substr(after + 12));
  CHECK(done >= 8);
  CHECK(done < 32);  // before the milder projection may speak
  CHECK(run.tets <= run.max_tets);
}

TEST_CASE(
    "insertion: the cut points a page makes inside itself are collapsed away, the embedding still exact",
    "[tetmesh][insertion]") {
  // Unsettled, every page cuts again the thin tets the pages below it left,
  // and keeps every point it cut inside itself.
  const TriangleSoup book = stacked_pages(300);
  InsertionOptions unsettled;
  unsettled.settle_cut_points = false;
  const Inserted plain = insert_soup(book, unsettled);
  const Inserted settled = insert_soup(book);
  require_exactly_embedded(book, plain);
  require_exactly_embedded(book, settled);
  CAPTURE(plain.background.mesh.num_tets(), settled.background.mesh.num_tets(), settled.stats.settled_points);
  CHECK(plain.stats.settled_points == 0);
  CHECK(settled.stats.settled_points > 0);
  CHECK(4 * settled.background.mesh.num_tets() < 3 * plain.background.mesh.num_tets());  // 0.62 measured
}
