// Stage 5: mesh improvement (split, collapse, swaps, smoothing) and rounding
// of rational vertices, on meshes built in code.

#include "test_support.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/envelope/envelope.h>
#include <mr/kernel/rounding.h>
#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/improve.h>
#include <mr/tetmesh/incidence.h>
#include <mr/tetmesh/mesh_check.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

using namespace mr;
using namespace mr::tetmesh;

namespace {

constexpr double kGridLo = -0.5;
constexpr double kGridStep = 0.25;
constexpr int kGridCells = 8;  // the grid spans [-0.5, 1.5]^3; the unit cube is inside

TetMesh kuhn_grid() { return test::kuhn_grid(kGridLo, kGridStep, kGridCells); }

bool in_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d n = (b - a).cross(c - a);
  if (std::abs(n.normalized().dot(p - a)) > 1e-12) return false;
  return (b - a).cross(p - a).dot(n) >= -1e-12 && (c - b).cross(p - b).dot(n) >= -1e-12 &&
         (a - c).cross(p - c).dot(n) >= -1e-12;
}

// True when the face lies in one face square of the unit cube.
bool on_unit_cube(const std::array<Vec3d, 3>& corners) {
  for (const Vec3d& p : corners) {
    if (p.minCoeff() < 0 || p.maxCoeff() > 1) return false;
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {0.0, 1.0}) {
      if (corners[0][axis] == side && corners[1][axis] == side && corners[2][axis] == side) return true;
    }
  }
  return false;
}

// Marks every mesh face on the unit cube's surface with the soup triangles
// containing its centre (two of them along a diagonal of a cube face).
void track_cube_surface(Mesh& mesh, const TriangleSoup& cube) {
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int f = 0; f < 4; ++f) {
      const auto c = mesh.face_vertices(t, f);
      const std::array<Vec3d, 3> p{mesh.position(c[0]).approx, mesh.position(c[1]).approx,
                                   mesh.position(c[2]).approx};
      if (!on_unit_cube(p)) continue;
      const Vec3d centre = (p[0] + p[1] + p[2]) / 3;
      std::vector<std::uint32_t> ids;
      for (std::uint32_t s = 0; s < cube.triangles.size(); ++s) {
        const auto& tri = cube.triangles[s];
        if (in_triangle(centre, cube.positions[tri[0]], cube.positions[tri[1]], cube.positions[tri[2]])) {
          ids.push_back(s);
        }
      }
      mesh.set_surface_ids(t, f, ids);
    }
  }
}

bool on_grid_hull(const Vec3d& p) {
  const double hi = kGridLo + kGridCells * kGridStep;
  for (int axis = 0; axis < 3; ++axis) {
    if (p[axis] == kGridLo || p[axis] == hi) return true;
  }
  return false;
}

// Jitters interior vertices (surface vertices within their plane) and
// squashes a few into slivers, keeping every tet strictly positive.
void damage(Mesh& mesh, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * kGridStep, 0.3 * kGridStep);
  const VertexTets incidence(mesh);
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    const Vec3d p = mesh.position(v).approx;
    if (on_grid_hull(p)) continue;
    Vec3d move(jitter(rng), jitter(rng), jitter(rng));
    if (mesh.has_flag(v, kOnSurface)) {
      for (int axis = 0; axis < 3; ++axis) {
        if (p[axis] == 0.0 || p[axis] == 1.0) move[axis] = 0;
      }
      const int fixed = int(p.x() == 0.0 || p.x() == 1.0) + int(p.y() == 0.0 || p.y() == 1.0) +
                        int(p.z() == 0.0 || p.z() == 1.0);
      if (fixed > 1) continue;  // cube edges and corners stay
    }
    const bool sliver = !mesh.has_flag(v, kOnSurface) && v % 23 == 0;
    for (const double scale :
         sliver ? std::vector<double>{3.3, 3.2, 3.0} : std::vector<double>{1.0, 0.5, 0.25}) {
      const HybridPoint before = mesh.position(v);
      mesh.position(v) = HybridPoint(Vec3d(p + scale * move));
      bool positive = true;
      for (const Index t : incidence.of(v)) {
        const Tet& c = mesh.tet(t);
        positive = positive && orient3d(mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]),
                                        mesh.position(c[3])) > 0;
      }
      if (positive) break;
      mesh.position(v) = before;
    }
  }
}

struct Fixture {
  TriangleSoup cube = test::cube_soup();
  Mesh mesh;
  std::unique_ptr<envelope::Envelope> envelope;

  explicit Fixture(unsigned seed = 7) {
    mesh = from_tet_mesh(kuhn_grid());
    for (Index v = 0; v < mesh.vertex_slots(); ++v) {
      if (on_grid_hull(mesh.position(v).approx)) mesh.add_flags(v, kOnBox);
    }
    track_cube_surface(mesh, cube);
    damage(mesh, seed);
    envelope::EnvelopeOptions options;
    options.epsilon = 1e-3 * std::sqrt(3.0);
    envelope = envelope::make_envelope(cube, options);
  }
};

ImproveOptions options_with_threads(int threads) {
  ImproveOptions options;
  options.target_edge_length = 0.25;
  options.max_passes = 8;
  options.threads = threads;
  return options;
}

struct TrackedSurface {
  std::size_t faces = 0;
  double area = 0;
  bool inside = true;
  bool ids_on_their_triangles = true;
  std::set<std::uint32_t> ids;
};

TrackedSurface tracked_surface(const Mesh& mesh, const TriangleSoup& cube, const envelope::Envelope& env) {
  TrackedSurface out;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int f = 0; f < 4; ++f) {
      if (!mesh.is_surface_face(t, f)) continue;
      const Index u = mesh.neighbour(t, f);
      if (u != kNoTet && u < t) continue;  // count each face once
      const auto c = mesh.face_vertices(t, f);
      const Vec3d &a = mesh.position(c[0]).approx, &b = mesh.position(c[1]).approx,
                  &d = mesh.position(c[2]).approx;
      ++out.faces;
      out.area += 0.5 * (b - a).cross(d - a).norm();
      out.inside = out.inside && env.is_inside(a, b, d);
      for (const std::uint32_t id : mesh.surface_ids(t, f)) {
        out.ids.insert(id);
        const auto& tri = cube.triangles[id];
        const Vec3d& p = cube.positions[tri[0]];
        const Vec3d n = (cube.positions[tri[1]] - p).cross(cube.positions[tri[2]] - p).normalized();
        for (const Vec3d* q : {&a, &b, &d}) {
          out.ids_on_their_triangles = out.ids_on_their_triangles && std::abs(n.dot(*q - p)) < 1e-9;
        }
      }
    }
  }
  return out;
}

bool all_tets_positive_on_doubles(const Mesh& mesh) {
  const check::TetReport report = check::check_tets(to_tet_mesh(mesh));
  return report.inverted_tets == 0 && report.degenerate_tets == 0;
}

}  // namespace

TEST_CASE("improve: the damaged fixture is valid and tracks the cube", "[improve]") {
  Fixture fixture;
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  const TrackedSurface surface = tracked_surface(fixture.mesh, fixture.cube, *fixture.envelope);
  CHECK(surface.faces == 6 * 4 * 4 * 2);
  CHECK(surface.area == Approx(6.0).epsilon(1e-12));
  CHECK(surface.inside);
  CHECK(surface.ids.size() == 12);
  CHECK(measure_quality(fixture.mesh).max_amips > 100);
}

TEST_CASE("improve: lowers the energy, keeps the mesh valid and the surface in place", "[improve]") {
  Fixture fixture;
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options_with_threads(2));
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  CHECK(all_tets_positive_on_doubles(fixture.mesh));
  CHECK(stats.after.max_amips < stats.before.max_amips);
  CHECK(stats.after.max_amips < 10);
  CHECK(stats.after.avg_amips < stats.before.avg_amips);
  CHECK(stats.after.min_dihedral_deg > stats.before.min_dihedral_deg);
  CHECK(stats.after.tets == fixture.mesh.num_tets());
  CHECK(stats.smoothing_moves > 0);
  CHECK(stats.rational_vertices == 0);

  const TrackedSurface surface = tracked_surface(fixture.mesh, fixture.cube, *fixture.envelope);
  CHECK(surface.inside);
  CHECK(surface.ids_on_their_triangles);
  CHECK(surface.ids.size() == 12);
  CHECK(surface.area == Approx(6.0).margin(4 * 12 * fixture.envelope->epsilon()));
}

TEST_CASE("improve: passes that end above the stop energy are polished without splits, never worse",
          "[improve]") {
  Fixture fixture;
  ImproveOptions options = options_with_threads(2);
  options.stop_energy = 3.01;  // a regular tet has 3: out of reach
  options.max_passes = 4;
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options);
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  CHECK(all_tets_positive_on_doubles(fixture.mesh));
  CHECK(stats.passes == 4);
  CHECK(stats.polish_passes >= 1);
  CHECK(stats.written_max_amips <= stats.passes_max_amips);
  CHECK(stats.after.max_amips == stats.written_max_amips);
  const TrackedSurface surface = tracked_surface(fixture.mesh, fixture.cube, *fixture.envelope);
  CHECK(surface.inside);
  CHECK(surface.ids.size() == 12);
}

TEST_CASE("improve: the floor of the local target halves around the last bad tets, never for the worse",
          "[improve][slow]") {
  // A stop energy hard to reach: the target shrinks to its floor around the
  // tets above it, and the passes stall there. The floor then halves, and
  // the best stage is written: never worse than stopping at the first floor.
  ImproveOptions options = options_with_threads(2);
  options.stop_energy = 4.2;
  options.min_sizing = 0.75;  // the first shrinking reaches it
  options.max_passes = 40;
  options.floor_halvings = 0;
  Fixture at_floor;
  const ImproveStats first = improve_mesh(at_floor.mesh, *at_floor.envelope, options);
  options.floor_halvings = 2;
  Fixture deeper;
  const ImproveStats halved = improve_mesh(deeper.mesh, *deeper.envelope, options);
  INFO("max AMIPS at the first floor " << first.written_max_amips << " after " << first.passes
                                       << " passes, halving " << halved.written_max_amips << " after "
                                       << halved.passes);
  CHECK(first.floor_halvings == 0);
  CHECK(halved.floor_halvings >= 1);
  CHECK(halved.written_max_amips <= first.written_max_amips);
  CHECK(halved.after.max_amips == halved.written_max_amips);
  REQUIRE(find_mesh_inconsistency(deeper.mesh) == "");
  CHECK(all_tets_positive_on_doubles(deeper.mesh));
  const TrackedSurface surface = tracked_surface(deeper.mesh, deeper.cube, *deeper.envelope);
  CHECK(surface.inside);
  CHECK(surface.ids.size() == 12);
}

TEST_CASE("improve: the tets left above the stop energy are reported worst first, by their freest corner",
          "[improve]") {
  Fixture fixture;
  ImproveOptions options = options_with_threads(2);
  options.stop_energy = 3.01;  // out of reach: every tet stays above it
  options.max_passes = 2;
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options);
  std::size_t above = 0;
  for (Index t = 0; t < fixture.mesh.tet_slots(); ++t) {
    if (!fixture.mesh.tet_alive(t)) continue;
    const Tet& c = fixture.mesh.tet(t);
    const auto at = [&](int i) { return fixture.mesh.position(c[i]).approx; };
    above += check::amips_energy(at(0), at(1), at(2), at(3)) >= options.stop_energy;
  }
  const StuckReport& stuck = stats.stuck;
  CHECK(stuck.tets == above);
  CHECK(stuck.free + stuck.sliding + stuck.creased + stuck.fixed == stuck.tets);
  CHECK(stuck.free > 0);     // tets inside the cube
  CHECK(stuck.sliding > 0);  // tets on a cube face, with no corner inside
  REQUIRE(stuck.worst.size() == 10);
  CHECK(stuck.worst.front().amips == stats.after.max_amips);
  for (std::size_t i = 1; i < stuck.worst.size(); ++i)
    CHECK(stuck.worst[i].amips <= stuck.worst[i - 1].amips);
  for (const StuckTet& t : stuck.worst) {
    CHECK((t.held_by == "free" || t.held_by == "sliding" || t.held_by == "creased" || t.held_by == "fixed"));
    for (const double x : t.centroid) CHECK((x > kGridLo && x < kGridLo + kGridCells * kGridStep));
  }
}

TEST_CASE("improve: tets whose every corner is locked are reported as fixed", "[improve]") {
  Fixture fixture;
  for (Index v = 0; v < fixture.mesh.vertex_slots(); ++v) fixture.mesh.add_flags(v, kLocked);
  ImproveOptions options = options_with_threads(2);
  options.max_passes = 1;
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options);
  REQUIRE(stats.stuck.tets > 0);  // the damaged fixture's bad tets stay as they are
  CHECK(stats.stuck.fixed == stats.stuck.tets);
}

TEST_CASE("improve: splits long edges and collapses short ones towards the target", "[improve][slow]") {
  Fixture fine;
  ImproveOptions coarse = options_with_threads(1);
  coarse.target_edge_length = 0.6;  // grid edges (0.25 .. 0.43) are short for it
  const std::size_t tets_before = fine.mesh.num_tets();
  const ImproveStats stats = improve_mesh(fine.mesh, *fine.envelope, coarse);
  REQUIRE(find_mesh_inconsistency(fine.mesh) == "");
  CHECK(stats.collapses > 0);
  CHECK(fine.mesh.num_tets() < tets_before);
  CHECK(all_tets_positive_on_doubles(fine.mesh));
  const TrackedSurface after_collapse = tracked_surface(fine.mesh, fine.cube, *fine.envelope);
  CHECK(after_collapse.inside);
  CHECK(after_collapse.ids.size() == 12);
  CHECK(after_collapse.area == Approx(6.0).margin(4 * 12 * fine.envelope->epsilon()));

  Fixture coarse_mesh;
  ImproveOptions fine_target = options_with_threads(1);
  fine_target.target_edge_length = 0.12;
  const ImproveStats split = improve_mesh(coarse_mesh.mesh, *coarse_mesh.envelope, fine_target);
  REQUIRE(find_mesh_inconsistency(coarse_mesh.mesh) == "");
  CHECK(split.splits > 0);
  CHECK(all_tets_positive_on_doubles(coarse_mesh.mesh));
  const TrackedSurface after_split =
      tracked_surface(coarse_mesh.mesh, coarse_mesh.cube, *coarse_mesh.envelope);
  CHECK(after_split.faces > 6 * 4 * 4 * 2);
  CHECK(after_split.inside);
  CHECK(after_split.ids_on_their_triangles);
  CHECK(after_split.area == Approx(6.0).margin(4 * 12 * coarse_mesh.envelope->epsilon()));
}

TEST_CASE("improve: same output for 1 and 2 threads", "[improve]") {
  Fixture one, two;
  const ImproveStats s1 = improve_mesh(one.mesh, *one.envelope, options_with_threads(1));
  const ImproveStats s2 = improve_mesh(two.mesh, *two.envelope, options_with_threads(2));
  CHECK(s1.splits == s2.splits);
  CHECK(s1.collapses == s2.collapses);
  CHECK(s1.smoothing_moves == s2.smoothing_moves);
  // Swaps are planned in parallel batches on two threads (swap_pass).
  CHECK(s1.swaps_32 + s1.swaps_23 + s1.swaps_44 + s1.edge_removals > 0);
  CHECK(s1.swaps_32 == s2.swaps_32);
  CHECK(s1.swaps_23 == s2.swaps_23);
  CHECK(s1.swaps_44 == s2.swaps_44);
  CHECK(s1.edge_removals == s2.edge_removals);
  CHECK(s1.after.max_amips == s2.after.max_amips);
  const TetMesh a = to_tet_mesh(one.mesh), b = to_tet_mesh(two.mesh);
  CHECK(a.positions == b.positions);
  CHECK(a.tets == b.tets);
}

// Per tet slot, kDropped for the tets outside the unit cube (by centroid).
std::vector<char> dropped_outside_the_cube(const Mesh& mesh) {
  std::vector<char> outside(mesh.tet_slots(), kWritten);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    Vec3d centre = Vec3d::Zero();
    for (const Index v : mesh.tet(t)) centre += mesh.position(v).approx / 4;
    outside[t] = centre.minCoeff() < 0 || centre.maxCoeff() > 1 ? kDropped : kWritten;
  }
  return outside;
}

// The largest energy of the tets inside the unit cube (by centroid).
double max_amips_inside_the_cube(const Mesh& mesh) {
  const std::vector<char> outside = dropped_outside_the_cube(mesh);
  double worst = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t) || outside[t] != kWritten) continue;
    const Tet& c = mesh.tet(t);
    worst = std::max(worst, check::amips_energy(mesh.position(c[0]).approx, mesh.position(c[1]).approx,
                                                mesh.position(c[2]).approx, mesh.position(c[3]).approx));
  }
  return worst;
}

TEST_CASE("improve: dropped tets neither drive nor block the passes", "[improve]") {
  Fixture whole, focused;
  const ImproveStats all = improve_mesh(whole.mesh, *whole.envelope, options_with_threads(2));
  TetPayload payload;
  payload.fate = dropped_outside_the_cube(focused.mesh);
  const ImproveStats inside = improve_mesh(focused.mesh, *focused.envelope, options_with_threads(2), payload);
  REQUIRE(find_mesh_inconsistency(focused.mesh) == "");
  CHECK(all_tets_positive_on_doubles(focused.mesh));
  const TrackedSurface surface = tracked_surface(focused.mesh, focused.cube, *focused.envelope);
  CHECK(surface.inside);
  CHECK(surface.ids.size() == 12);
  // The cube's tets reach the stop energy with less work; the tets around
  // it (the damage put slivers there too) are left as they are.
  CHECK(inside.written_max_amips < 10);
  CHECK(max_amips_inside_the_cube(focused.mesh) < 10);
  CHECK(inside.splits + inside.collapses + inside.smoothing_moves <
        all.splits + all.collapses + all.smoothing_moves);
  CHECK(inside.after.max_amips > all.after.max_amips);
}

TEST_CASE("improve: a value per tet follows the tets through every operation", "[improve]") {
  // 1 inside the tracked cube, 0 outside: no operation moves a tet across
  // a tracked face, so every tet made from one keeps the side it is on.
  Fixture fixture;
  TetPayload payload;
  const std::vector<char> outside = dropped_outside_the_cube(fixture.mesh);
  for (const char fate : outside) payload.value.push_back(fate == kDropped ? 0.0 : 1.0);
  ImproveOptions options = options_with_threads(2);
  options.target_edge_length = 0.15;  // splits as well as collapses and swaps
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options, payload);
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  CHECK(stats.splits > 0);
  CHECK(stats.collapses > 0);
  CHECK(stats.swaps_23 + stats.swaps_32 + stats.swaps_44 + stats.edge_removals > 0);
  REQUIRE(payload.value.size() == fixture.mesh.tet_slots());
  CHECK(payload.fate.empty());
  const double margin = fixture.envelope->epsilon();
  std::size_t inside = 0, wrong = 0;
  for (Index t = 0; t < fixture.mesh.tet_slots(); ++t) {
    if (!fixture.mesh.tet_alive(t)) continue;
    Vec3d centre = Vec3d::Zero();
    for (const Index v : fixture.mesh.tet(t)) centre += fixture.mesh.position(v).approx / 4;
    const bool surely_in = centre.minCoeff() > margin && centre.maxCoeff() < 1 - margin;
    const bool surely_out = centre.minCoeff() < -margin || centre.maxCoeff() > 1 + margin;
    inside += payload.value[t] == 1.0;
    wrong += (payload.value[t] == 1.0 && surely_out) || (payload.value[t] == 0.0 && surely_in);
  }
  CHECK(inside > 0);
  CHECK(wrong == 0);
}

TEST_CASE("improve: a mesh dropped everywhere is left as it is", "[improve]") {
  Fixture fixture;
  const TetMesh before = to_tet_mesh(fixture.mesh);
  TetPayload payload;
  payload.fate.assign(fixture.mesh.tet_slots(), kDropped);
  const ImproveStats stats = improve_mesh(fixture.mesh, *fixture.envelope, options_with_threads(2), payload);
  CHECK(stats.passes == 0);
  CHECK(stats.written_max_amips == 0);
  const TetMesh after = to_tet_mesh(fixture.mesh);
  CHECK(after.positions == before.positions);
  CHECK(after.tets == before.tets);
  payload.fate.pop_back();
  CHECK_THROWS_AS(improve_mesh(fixture.mesh, *fixture.envelope, options_with_threads(2), payload),
                  UsageError);
}

TEST_CASE("improve: locked vertices never move", "[improve]") {
  Fixture fixture;
  std::vector<std::pair<Index, Vec3d>> locked;
  for (Index v = 0; v < fixture.mesh.vertex_slots(); v += 5) {
    fixture.mesh.add_flags(v, kLocked);
    locked.emplace_back(v, fixture.mesh.position(v).approx);
  }
  improve_mesh(fixture.mesh, *fixture.envelope, options_with_threads(2));
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  for (const auto& [v, p] : locked) {
    REQUIRE(fixture.mesh.vertex_alive(v));
    CHECK(fixture.mesh.position(v).approx == p);
  }
}

TEST_CASE("improve: bad options are usage errors", "[improve]") {
  Fixture fixture;
  ImproveOptions options;
  CHECK_THROWS_AS(improve_mesh(fixture.mesh, *fixture.envelope, options), UsageError);
  options.target_edge_length = 0.25;
  options.stop_energy = -1;
  CHECK_THROWS_AS(improve_mesh(fixture.mesh, *fixture.envelope, options), UsageError);
  options.stop_energy = 10;
  options.floor_halvings = -1;
  CHECK_THROWS_AS(improve_mesh(fixture.mesh, *fixture.envelope, options), UsageError);
}

TEST_CASE("improve: split_edge keeps the ids on both halves of a tracked face", "[improve]") {
  Fixture fixture;
  // A tracked edge: two surface vertices of one tracked face.
  Index a = kNoVertex, b = kNoVertex;
  for (Index t = 0; t < fixture.mesh.tet_slots() && a == kNoVertex; ++t) {
    for (int f = 0; f < 4 && a == kNoVertex; ++f) {
      if (!fixture.mesh.is_surface_face(t, f)) continue;
      a = fixture.mesh.face_vertices(t, f)[0];
      b = fixture.mesh.face_vertices(t, f)[1];
    }
  }
  REQUIRE(a != kNoVertex);
  const TrackedSurface before = tracked_surface(fixture.mesh, fixture.cube, *fixture.envelope);
  const Vec3d middle = 0.5 * (fixture.mesh.position(a).approx + fixture.mesh.position(b).approx);
  const Index m = split_edge(fixture.mesh, a, b, HybridPoint(middle));
  REQUIRE(m != kNoVertex);
  REQUIRE(find_mesh_inconsistency(fixture.mesh) == "");
  CHECK(fixture.mesh.has_flag(m, kOnSurface));
  const TrackedSurface after = tracked_surface(fixture.mesh, fixture.cube, *fixture.envelope);
  CHECK(after.faces == before.faces + 2);  // an interior surface edge has two tracked faces
  CHECK(after.ids == before.ids);
  CHECK(after.ids_on_their_triangles);
  CHECK(after.area == Approx(before.area).epsilon(1e-12));
  // Not an edge, or a point outside the edge's star: refused, mesh untouched.
  CHECK(split_edge(fixture.mesh, a, a, HybridPoint(middle)) == kNoVertex);
  CHECK(split_edge(fixture.mesh, a, m, HybridPoint(Vec3d(5, 5, 5))) == kNoVertex);
  CHECK(find_mesh_inconsistency(fixture.mesh) == "");
}

// Vertex (0.5, 0.5, 0.5) of the grid and its neighbour along +x: an interior edge.
constexpr Index kGridA = (4 * 9 + 4) * 9 + 4;
constexpr Index kGridB = kGridA + 1;

std::unique_ptr<envelope::Envelope> unit_cube_envelope() {
  envelope::EnvelopeOptions options;
  options.epsilon = 1e-3;
  return envelope::make_envelope(test::cube_soup(), options);
}

TEST_CASE("improve: round_vertices rounds a rational vertex whose nearest doubles are flat", "[improve]") {
  Mesh mesh = from_tet_mesh(kuhn_grid());
  REQUIRE(mesh.position(kGridA).approx == Vec3d(0.5, 0.5, 0.5));
  REQUIRE(mesh.position(kGridB).approx == Vec3d(0.75, 0.5, 0.5));
  // A hair from vertex A along the edge: its nearest doubles are A itself,
  // which would flatten every new tet holding both.
  const mpq_class x = mpq_class(1, 2) + mpq_class(1, mpz_class(1) << 80);
  const Index v = split_edge(mesh, kGridA, kGridB, HybridPoint::from_exact(ExactPoint3(x, 0.5, 0.5)));
  REQUIRE(v != kNoVertex);
  REQUIRE(mesh.position(v).is_exact());
  REQUIRE(find_mesh_inconsistency(mesh) == "");

  std::vector<Tet> incident;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t) && mesh.corner_of(t, v) >= 0) incident.push_back(mesh.tet(t));
  }
  std::vector<HybridPoint> positions;
  for (Index w = 0; w < mesh.vertex_slots(); ++w) positions.push_back(mesh.position(w));
  REQUIRE_FALSE(try_round_vertex(positions, v, incident));  // in-place rounding alone fails

  const RoundingStats stats = round_vertices(mesh, *unit_cube_envelope());
  CHECK(stats.rational_before == 1);
  CHECK(stats.remaining == 0);
  CHECK(stats.rounded == 0);
  CHECK(stats.moved + stats.collapsed == 1);
  REQUIRE(find_mesh_inconsistency(mesh) == "");
  for (Index w = 0; w < mesh.vertex_slots(); ++w) {
    if (mesh.vertex_alive(w)) CHECK_FALSE(mesh.position(w).is_exact());
  }
  CHECK(all_tets_positive_on_doubles(mesh));
}

TEST_CASE("improve: round_vertices rounds in place when that is safe", "[improve]") {
  Mesh mesh = from_tet_mesh(kuhn_grid());
  const Index v =
      split_edge(mesh, kGridA, kGridB, HybridPoint::from_exact(ExactPoint3(mpq_class(3, 5), 0.5, 0.5)));
  REQUIRE(v != kNoVertex);
  REQUIRE(mesh.position(v).is_exact());
  const RoundingStats stats = round_vertices(mesh, *unit_cube_envelope());
  CHECK(stats.rounded == 1);
  CHECK(stats.remaining == 0);
  CHECK_FALSE(mesh.position(v).is_exact());
  CHECK(find_mesh_inconsistency(mesh) == "");
  CHECK(all_tets_positive_on_doubles(mesh));
}

namespace {

// The n needles around the edge from (0, 0, -3) to (0, 0, 3), their far
// corners on the unit circle; every vertex locked, so only swaps can act.
Mesh needles_around_an_edge(int n) {
  Mesh mesh;
  const Index a = mesh.add_vertex(HybridPoint(Vec3d(0, 0, -3)), kLocked);
  const Index b = mesh.add_vertex(HybridPoint(Vec3d(0, 0, 3)), kLocked);
  std::vector<Index> ring;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * M_PI * i / n;
    ring.push_back(mesh.add_vertex(HybridPoint(Vec3d(std::cos(angle), std::sin(angle), 0)), kLocked));
  }
  for (int i = 0; i < n; ++i) {
    const Index x = ring[i], y = ring[(i + 1) % n];
    const Vec3d &pa = mesh.position(a).approx, &pb = mesh.position(b).approx, &px = mesh.position(x).approx,
                &py = mesh.position(y).approx;
    const bool positive = (pb - pa).cross(px - pa).dot(py - pa) > 0;
    mesh.add_tet(positive ? Tet{a, b, x, y} : Tet{a, b, y, x});
  }
  mesh.rebuild_adjacency();
  return mesh;
}

bool has_edge(const Mesh& mesh, Index a, Index b) {
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t) && mesh.corner_of(t, a) >= 0 && mesh.corner_of(t, b) >= 0) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("improve: an edge in five or six needles is removed", "[improve]") {
  // No 3-2 or 4-4 swap applies, and the 2-3 swaps raise the largest energy:
  // only removing the edge whole (2n - 4 tets on a triangulation of the
  // ring) improves these.
  const int n = GENERATE(5, 6);
  Mesh mesh = needles_around_an_edge(n);
  REQUIRE(find_mesh_inconsistency(mesh).empty());
  const double before = measure_quality(mesh).max_amips;
  ImproveOptions options = options_with_threads(1);
  options.target_edge_length = 100;  // nothing to split
  options.stop_energy = 3.5;
  options.max_passes = 4;
  const ImproveStats stats = improve_mesh(mesh, *unit_cube_envelope(), options);
  CHECK(find_mesh_inconsistency(mesh).empty());
  CHECK(stats.edge_removals >= 1);
  CHECK_FALSE(has_edge(mesh, 0, 1));
  CHECK(stats.after.max_amips < 0.8 * before);
}
