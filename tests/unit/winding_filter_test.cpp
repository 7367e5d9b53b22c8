// Stage 6 on meshes built in code: the winding number of an open tracked
// surface carried from tet to tet by crossings, or asked of the input away
// from where the mesh moved it; a closed input with triangles left out
// decided per region.

#include "test_support.h"

#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/mesh_check.h>
#include <mr/tetmesh/open_surface_winding.h>
#include <mr/tetmesh/winding_filter.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

using namespace mr;
using namespace mr::tetmesh;

namespace {

constexpr double kLo = -0.5;
constexpr double kStep = 0.25;
constexpr int kCells = 8;  // the grid spans [-0.5, 1.5]^3

bool on_box(const Vec3d& p) {
  const bool inside = p.minCoeff() >= 0.0 && p.maxCoeff() <= 1.0;
  return inside && (p.minCoeff() == 0.0 || p.maxCoeff() == 1.0);
}

// The grid faces on the unit cube, without its top (z = 1) when `open`: the
// input soup, oriented outward, each face marked with its triangle's id.
TriangleSoup mark_box(Mesh& mesh, bool open = true) {
  TriangleSoup box;
  std::map<std::array<Index, 3>, std::uint32_t> ids;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int k = 0; k < 4; ++k) {
      std::array<Index, 3> f = mesh.face_vertices(t, k);
      const Vec3d a = mesh.position(f[0]).approx, b = mesh.position(f[1]).approx,
                  c = mesh.position(f[2]).approx;
      if (!on_box(a) || !on_box(b) || !on_box(c)) continue;
      const Vec3d normal = (b - a).cross(c - a);
      const Vec3d centre = (a + b + c) / 3.0;
      // A face on the box lies in one of its planes: the normal is along an axis.
      if (normal.cwiseAbs().maxCoeff() != normal.norm()) continue;
      int axis = 0;
      normal.cwiseAbs().maxCoeff(&axis);
      if (centre[axis] != 0.0 && centre[axis] != 1.0) continue;
      if (open && axis == 2 && centre[axis] == 1.0) continue;  // the open top
      std::array<Index, 3> key = f;
      std::sort(key.begin(), key.end());
      auto [it, added] = ids.try_emplace(key, static_cast<std::uint32_t>(box.triangles.size()));
      if (added) {
        if (normal.dot(centre - Vec3d(0.5, 0.5, 0.5)) < 0) std::swap(f[1], f[2]);
        box.triangles.push_back({f[0], f[1], f[2]});
      }
      const std::uint32_t id = it->second;
      mesh.set_surface_ids(t, k, std::span<const std::uint32_t>(&id, 1));
    }
  }
  for (Index v = 0; v < mesh.vertex_slots(); ++v) box.positions.push_back(mesh.position(v).approx);
  return box;
}

// The marked faces with the mesh's current positions, oriented like their
// triangles: what the tracked surface is.
TriangleSoup tracked_faces(const Mesh& mesh, const TriangleSoup& input) {
  TriangleSoup tracked = input;
  for (Index v = 0; v < mesh.vertex_slots(); ++v) tracked.positions[v] = mesh.position(v).approx;
  return tracked;
}

// Moves the grid vertex at the centre of the box's bottom, (0.5, 0.5, 0),
// down by 0.01: the tracked surface strays from the input there.
void move_bottom_centre_down(Mesh& mesh) {
  const Index bottom_centre = (2 * (kCells + 1) + 4) * (kCells + 1) + 4;
  REQUIRE(mesh.position(bottom_centre).approx == Vec3d(0.5, 0.5, 0.0));
  mesh.position(bottom_centre) = HybridPoint(Vec3d(0.5, 0.5, -0.01));
}

// Per triangle of a soup made by mark_box, the face it marks.
std::vector<FaceRef> marked_faces(const Mesh& mesh, std::size_t triangles) {
  std::vector<FaceRef> origins(triangles, FaceRef{kNoTet, 0});
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int k = 0; k < 4; ++k) {
      for (const std::uint32_t id : mesh.surface_ids(t, k)) {
        if (origins[id].tet == kNoTet) origins[id] = {t, k};
      }
    }
  }
  return origins;
}

// How far `winding` (per tet slot) is at most from the winding number of
// `surface` at the live tets' centroids, summed triangle by triangle. The
// trees' far-field expansions are good to a few thousandths here; a wrong
// crossing count would be off by one.
double largest_error(const Mesh& mesh, const std::vector<double>& winding, const TriangleSoup& surface) {
  double largest = 0.0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t))
      largest =
          std::max(largest, std::abs(winding[t] - winding_number_exact(surface, tet_centroid(mesh, t))));
  }
  return largest;
}
constexpr double kTreeError = 0.01;

// The tracked surface of a box marked by mark_box, its winding numbers
// carried by crossings, and every tet's own.
struct CarriedAndAsked {
  TriangleSoup surface;
  std::vector<double> carried;
  TetClassification asked;
  OpenWindingStats stats;
};
CarriedAndAsked carry_and_ask(const Mesh& mesh, const TriangleSoup& input) {
  CarriedAndAsked out;
  out.surface = tracked_faces(mesh, input);
  out.carried =
      open_surface_winding(mesh, out.surface, marked_faces(mesh, out.surface.triangles.size()), out.stats);
  out.asked = classify_tets(mesh, WindingNumberTree(out.surface), WindingRule::absolute);
  return out;
}

}  // namespace

TEST_CASE("winding filter: an open surface's winding number carried from tet to tet by crossings",
          "[tetmesh][filter]") {
  Mesh mesh = from_tet_mesh(test::kuhn_grid(kLo, kStep, kCells));
  TriangleSoup input = mark_box(mesh);
  REQUIRE(input.triangles.size() == 5 * 4 * 4 * 2);

  SECTION("embedded exactly: the number every tet's own query gives") {
    const auto [surface, carried, all, stats] = carry_and_ask(mesh, input);
    CHECK(stats.cap_triangles == 14);  // the rim of the open top: 16 grid edges, closed by 14 triangles
    // Segments that pass beside the face between their tets, or through an edge.
    CHECK(stats.full_crossing_tests < mesh.num_tets() / 100);
    CHECK(stats.direct_queries >= 1);  // the first tet
    CHECK(stats.direct_queries < mesh.num_tets() / 100);
    CHECK(largest_error(mesh, carried, surface) < kTreeError);
    const TetClassification classes = classify_by_winding(mesh, carried, WindingRule::absolute);
    CHECK(classes.keep == all.keep);
    // The open box keeps the tets inside it: (4 x 4 x 4 cells) x 6.
    CHECK(classes.kept == 4 * 4 * 4 * 6);
  }

  SECTION("a vertex moved off the bottom: still the tracked surface's number") {
    move_bottom_centre_down(mesh);
    const auto [surface, carried, all, stats] = carry_and_ask(mesh, input);
    CHECK(largest_error(mesh, carried, surface) < kTreeError);
    CHECK(classify_by_winding(mesh, carried, WindingRule::absolute).keep == all.keep);
  }

  SECTION("the same surface twice (multiplicity 2) and once reversed (winding -1)") {
    TriangleSoup twice = tracked_faces(mesh, input);
    const std::size_t n = twice.triangles.size();
    std::vector<FaceRef> origins = marked_faces(mesh, n);
    for (std::size_t i = 0; i < n; ++i) {
      twice.triangles.push_back(twice.triangles[i]);
      origins.push_back(origins[i]);
    }
    OpenWindingStats stats;
    const WindingNumberTree tree(twice);
    const std::vector<double> carried = open_surface_winding(mesh, twice, origins, stats);
    CHECK(stats.cap_triangles == 28);  // two loops
    CHECK(largest_error(mesh, carried, twice) < 2 * kTreeError);

    TriangleSoup reversed = tracked_faces(mesh, input);
    for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
    const WindingNumberTree reversed_tree(reversed);
    const std::vector<double> negative = open_surface_winding(mesh, reversed, marked_faces(mesh, n), stats);
    CHECK(largest_error(mesh, negative, reversed) < kTreeError);
    CHECK(*std::min_element(negative.begin(), negative.end()) < -0.9);
  }

  SECTION("no surface: zero everywhere") {
    OpenWindingStats stats;
    const std::vector<double> carried = open_surface_winding(mesh, TriangleSoup{}, {}, stats);
    CHECK(stats.cap_triangles == 0);
    CHECK(std::all_of(carried.begin(), carried.end(), [](double w) { return w == 0.0; }));
  }
}

TEST_CASE("winding filter: an open surface is asked of the input away from where the mesh moved it",
          "[tetmesh][filter]") {
  Mesh mesh = from_tet_mesh(test::kuhn_grid(kLo, kStep, kCells));
  const TriangleSoup input = mark_box(mesh);
  REQUIRE(input.triangles.size() == 5 * 4 * 4 * 2);
  const std::vector<char> none_left_out(input.triangles.size(), 0);

  SECTION("embedded exactly: no tet needs the tracked surface, and the result is the same") {
    const std::vector<double> offsets = tracked_surface_offsets(mesh, input);
    REQUIRE(std::all_of(offsets.begin(), offsets.end(), [](double d) { return d == 0.0; }));
    const WindingNumberTree tracked(tracked_faces(mesh, input));
    std::size_t near = 1;
    const TetClassification fast =
        classify_tets_near_input(mesh, tracked, input, none_left_out, offsets, WindingRule::absolute, &near);
    const TetClassification all = classify_tets(mesh, tracked, WindingRule::absolute);
    CHECK(near == 0);
    CHECK(fast.keep == all.keep);
    CHECK(fast.winding == all.winding);
    // The open box keeps the tets inside it: (4 x 4 x 4 cells) x 6.
    CHECK(fast.kept == 4 * 4 * 4 * 6);
  }

  SECTION("a moved vertex: tets near it ask the tracked surface, the others agree with it") {
    move_bottom_centre_down(mesh);
    const std::vector<double> offsets = tracked_surface_offsets(mesh, input);
    CHECK(*std::max_element(offsets.begin(), offsets.end()) == Approx(0.01));
    CHECK(std::count(offsets.begin(), offsets.end(), 0.0) ==
          static_cast<long>(input.triangles.size()) - 6);  // its star on the bottom

    const WindingNumberTree tracked(tracked_faces(mesh, input));
    std::size_t near = 0;
    const TetClassification fast =
        classify_tets_near_input(mesh, tracked, input, none_left_out, offsets, WindingRule::absolute, &near);
    const TetClassification all = classify_tets(mesh, tracked, WindingRule::absolute);
    CHECK(near > 0);
    CHECK(near < mesh.num_tets() / 10);
    CHECK(fast.keep == all.keep);
    double largest_difference = 0.0;
    for (Index t = 0; t < mesh.tet_slots(); ++t) {
      largest_difference = std::max(largest_difference, std::abs(fast.winding[t] - all.winding[t]));
    }
    CHECK(largest_difference < 0.01);
  }

  SECTION("triangles left out are not part of the chain") {
    std::vector<char> left_out(input.triangles.size(), 1);
    const WindingNumberTree tracked(TriangleSoup{});
    const TetClassification fast =
        classify_tets_near_input(mesh, tracked, input, left_out,
                                 std::vector<double>(input.triangles.size(), 0.0), WindingRule::absolute);
    CHECK(fast.kept == 0);
  }
}

TEST_CASE("winding filter: a closed input with a triangle left out is decided per region, the hole plugged",
          "[tetmesh][filter]") {
  Mesh mesh = from_tet_mesh(test::kuhn_grid(kLo, kStep, kCells));
  const TriangleSoup box = mark_box(mesh, /*open=*/false);
  REQUIRE(box.triangles.size() == 6 * 4 * 4 * 2);
  // Leave triangle 0 out: unmark its face, which opens the tracked surface.
  TriangleSoup hole;
  hole.positions = box.positions;
  hole.triangles.push_back(box.triangles[0]);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int k = 0; k < 4; ++k) {
      const auto ids = mesh.surface_ids(t, k);
      if (ids.size() == 1 && ids.front() == 0) mesh.set_surface_ids(t, k, {});
    }
  }
  const WindingNumberTree input(box);
  const std::vector<char> barrier = tets_near(mesh, hole);
  const auto barrier_tets = std::count(barrier.begin(), barrier.end(), 1);
  CHECK(barrier_tets >= 2);  // at least the two tets on either side of the hole
  CHECK(barrier_tets <
        static_cast<long>(mesh.num_tets()) / 5);  // the doubled bounding spheres reach a cell or two

  // Without the barrier the inside leaks out through the hole: one region.
  const TetClassification leaking = classify_regions(mesh, input, WindingRule::absolute);
  CHECK(leaking.kept == 0);
  // With it, the box is kept whole, as every tet's own winding number says.
  const TetClassification plugged = classify_regions(mesh, input, WindingRule::absolute, barrier);
  const TetClassification per_tet = classify_tets(mesh, input, WindingRule::absolute);
  CHECK(plugged.kept == 4 * 4 * 4 * 6);
  CHECK(plugged.keep == per_tet.keep);
}

namespace {

// Two triangles of the rectangle origin + [0, 1] u + [0, 1] v, split along
// origin -> origin + u + v (the direction of the Kuhn grid's face
// diagonals), facing `outward`.
void add_rectangle(TriangleSoup& soup, const Vec3d& origin, const Vec3d& u, const Vec3d& v,
                   const Vec3d& outward) {
  const bool flip = u.cross(v).dot(outward) < 0.0;
  const std::array<Vec3d, 3> first{origin, origin + u, origin + u + v};
  const std::array<Vec3d, 3> second{origin, origin + u + v, origin + v};
  for (std::array<Vec3d, 3> corners : {first, second}) {
    if (flip) std::swap(corners[1], corners[2]);
    const Index base = static_cast<Index>(soup.positions.size());
    soup.positions.insert(soup.positions.end(), corners.begin(), corners.end());
    soup.triangles.push_back({base, base + 1, base + 2});
  }
}

// Whether p lies in triangle i of `soup` (which lies in an axis plane): on
// its plane and inside it, edges included.
bool in_axis_triangle(const TriangleSoup& soup, std::size_t i, const Vec3d& p) {
  const Vec3d a = soup.positions[soup.triangles[i][0]], b = soup.positions[soup.triangles[i][1]],
              c = soup.positions[soup.triangles[i][2]];
  const Vec3d n = (b - a).cross(c - a);
  if (n.dot(p - a) != 0.0) return false;
  const auto side = [&](const Vec3d& x, const Vec3d& y) { return n.dot((y - x).cross(p - x)) >= 0.0; };
  return side(a, b) && side(b, c) && side(c, a);
}

double distance_to_box_surface(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  const Vec3d outside = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
  if (outside.norm() > 0.0) return outside.norm();
  return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
}

}  // namespace

TEST_CASE("winding filter: barrier tets that straddle a left-out triangle are refined into the envelope",
          "[tetmesh][filter]") {
  // A closed box whose top (z = 0.875) lies halfway through a layer of grid
  // cells. Its bottom and the sides up to z = 0.75 are grid faces and are
  // marked; the top and the strips of the sides above z = 0.75 are not (as
  // if insertion had left them out). The barrier tets around them reach
  // z = 1, 0.125 above the top.
  Mesh mesh = from_tet_mesh(test::kuhn_grid(kLo, kStep, kCells));
  const Vec3d lo(0.0, 0.0, 0.0), hi(0.75, 0.75, 0.875);
  const double wall = 0.75, strip = 0.125;
  TriangleSoup box;
  const Vec3d x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  add_rectangle(box, lo, wall * x, wall * y, -z);                 // bottom
  add_rectangle(box, Vec3d(0, 0, 0.875), wall * x, wall * y, z);  // top
  for (const double at : {0.0, 0.75}) {
    const Vec3d out = at == 0.0 ? Vec3d(-1, 0, 0) : Vec3d(1, 0, 0);
    add_rectangle(box, Vec3d(at, 0, 0), wall * y, wall * z, out);
    add_rectangle(box, Vec3d(at, 0, 0.75), wall * y, strip * z, out);
    const Vec3d out_y = at == 0.0 ? Vec3d(0, -1, 0) : Vec3d(0, 1, 0);
    add_rectangle(box, Vec3d(0, at, 0), wall * x, wall * z, out_y);
    add_rectangle(box, Vec3d(0, at, 0.75), wall * x, strip * z, out_y);
  }
  REQUIRE(box.triangles.size() == 20);

  std::vector<char> used(box.triangles.size(), 0);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int k = 0; k < 4; ++k) {
      const std::array<Index, 3> f = mesh.face_vertices(t, k);
      for (std::size_t i = 0; i < box.triangles.size(); ++i) {
        const bool inside = std::all_of(
            f.begin(), f.end(), [&](Index v) { return in_axis_triangle(box, i, mesh.position(v).approx); });
        if (!inside) continue;
        const std::uint32_t id = static_cast<std::uint32_t>(i);
        mesh.set_surface_ids(t, k, std::span<const std::uint32_t>(&id, 1));
        for (const Index v : f) mesh.add_flags(v, kOnSurface);
        used[i] = 1;
      }
    }
  }
  TriangleSoup holes;
  holes.positions = box.positions;
  for (std::size_t i = 0; i < box.triangles.size(); ++i) {
    if (used[i] == 0) holes.triangles.push_back(box.triangles[i]);
  }
  REQUIRE(holes.triangles.size() == 10);  // the top and the four strips
  REQUIRE(find_mesh_inconsistency(mesh).empty());

  const double epsilon = 0.05;
  envelope::EnvelopeOptions envelope_options;
  envelope_options.epsilon = epsilon;
  const std::unique_ptr<envelope::Envelope> envelope = envelope::make_envelope(box, envelope_options);
  const WindingNumberTree input(box);

  SECTION("without refinement, the boundary runs along the far faces of barrier tets") {
    BarrierRefinementOptions options;
    options.max_rounds = 0;
    BarrierRefinementStats stats;
    classify_with_refined_barrier(mesh, holes, input, WindingRule::absolute, *envelope, options, stats);
    CHECK(stats.faces_outside > 0);
    CHECK(stats.splits == 0);
  }

  SECTION("refined, every boundary face lies within epsilon of the box and the mesh stays valid") {
    BarrierRefinementStats stats;
    const TetClassification classes =
        classify_with_refined_barrier(mesh, holes, input, WindingRule::absolute, *envelope, {}, stats);
    CHECK(stats.faces_outside == 0);
    CHECK(stats.splits > 0);
    CHECK(stats.rounds > 0);
    CHECK(find_mesh_inconsistency(mesh).empty());

    double volume = 0.0, farthest = 0.0;
    for (Index t = 0; t < mesh.tet_slots(); ++t) {
      if (!mesh.tet_alive(t) || classes.keep[t] == 0) continue;
      const Tet& c = mesh.tet(t);
      const Vec3d a = mesh.position(c[0]).approx;
      volume += (mesh.position(c[1]).approx - a)
                    .cross(mesh.position(c[2]).approx - a)
                    .dot(mesh.position(c[3]).approx - a) /
                6.0;
      for (int k = 0; k < 4; ++k) {
        const Index n = mesh.neighbour(t, k);
        if (n != kNoTet && classes.keep[n] != 0) continue;
        Vec3d centre = Vec3d::Zero();
        for (const Index v : mesh.face_vertices(t, k)) {
          farthest = std::max(farthest, distance_to_box_surface(mesh.position(v).approx, lo, hi));
          centre += mesh.position(v).approx / 3.0;
        }
        farthest = std::max(farthest, distance_to_box_surface(centre, lo, hi));
      }
    }
    CHECK(farthest <= epsilon);
    const double area = 2 * 0.75 * 0.75 + 4 * 0.75 * 0.875;
    CHECK(std::abs(volume - 0.75 * 0.75 * 0.875) <= area * epsilon);
  }
}
