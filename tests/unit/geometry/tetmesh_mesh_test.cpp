// The pipeline's mutable tet mesh: adjacency, marks, removal and reuse,
// hybrid vertices, conversion, and the invariant checker catching damage.

#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/kernel/rounding.h>
#include <mr/spatial/aabb_tree.h>
#include <mr/tetmesh/background_mesh.h>
#include <mr/tetmesh/convert.h>
#include <mr/tetmesh/incidence.h>
#include <mr/tetmesh/mesh_check.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

using namespace mr;
using namespace mr::tetmesh;

namespace {

std::size_t count_free_faces(const Mesh& mesh) {
  std::size_t free = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int f = 0; f < 4; ++f) free += mesh.neighbour(t, f) == kNoTet;
  }
  return free;
}

// Two tets sharing face (0, 1, 2): apex 3 above, apex 4 below (or above when `overlap`).
TetMesh two_tets(bool overlap) {
  TetMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 1}, {0.2, 0.2, overlap ? 0.5 : -1}};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  if (overlap) m.tets[1] = {0, 1, 2, 4};
  return m;
}

// Splits tet t at a new vertex p (1-to-4), the way a cut replaces a cavity.
Index split_tet(Mesh& mesh, Index t, const HybridPoint& p) {
  const Tet old = mesh.tet(t);
  std::vector<Index> around;
  for (int f = 0; f < 4; ++f) {
    if (mesh.neighbour(t, f) != kNoTet) around.push_back(mesh.neighbour(t, f));
  }
  mesh.remove_tet(t);
  const Index v = mesh.add_vertex(p);
  std::vector<Index> cavity = around;
  for (int k = 0; k < 4; ++k) {
    Tet piece = old;
    piece[k] = v;  // replacing corner k keeps the orientation
    cavity.push_back(mesh.add_tet(piece));
  }
  mesh.connect(cavity);
  return v;
}

}  // namespace

TEST_CASE("tetmesh: cube tets convert with symmetric adjacency and round-trip", "[tetmesh]") {
  const TetMesh cube = test::cube_tets();
  const Mesh mesh = from_tet_mesh(cube);
  CHECK(find_mesh_inconsistency(mesh).empty());
  CHECK(mesh.num_tets() == 6);
  CHECK(count_free_faces(mesh) == 12);  // two triangles per cube face

  const TetMesh back = to_tet_mesh(mesh);
  CHECK(back.positions == cube.positions);
  CHECK(back.tets == cube.tets);
}

TEST_CASE("tetmesh: face_vertices point out of their tet", "[tetmesh]") {
  const Mesh mesh = from_tet_mesh(test::cube_tets());
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    for (int f = 0; f < 4; ++f) {
      const auto face = mesh.face_vertices(t, f);
      CHECK(orient3d(mesh.position(face[0]), mesh.position(face[1]), mesh.position(face[2]),
                     mesh.position(mesh.tet(t)[f])) < 0);
    }
  }
}

TEST_CASE("tetmesh: the checker catches an inverted tet", "[tetmesh]") {
  TetMesh cube = test::cube_tets();
  std::swap(cube.tets[3][1], cube.tets[3][2]);
  const std::string problem = find_mesh_inconsistency(from_tet_mesh(cube));
  CHECK(problem.find("tet 3 is not positively oriented") != std::string::npos);
}

TEST_CASE("tetmesh: the checker catches overlapping neighbours", "[tetmesh]") {
  CHECK(find_mesh_inconsistency(from_tet_mesh(two_tets(false))).empty());
  const std::string problem = find_mesh_inconsistency(from_tet_mesh(two_tets(true)));
  CHECK(problem.find("opposite sides") != std::string::npos);
}

TEST_CASE("tetmesh: the checker catches corrupted adjacency", "[tetmesh]") {
  Mesh mesh = from_tet_mesh(test::cube_tets());
  SECTION("a face glued to a tet with other corners") {
    const int free_face = [&] {
      for (int f = 0; f < 4; ++f) {
        if (mesh.neighbour(0, f) == kNoTet) return f;
      }
      return -1;
    }();
    REQUIRE(free_face >= 0);
    const Index far = 3;  // Kuhn tets 0 and 3 share only the diagonal
    REQUIRE(mesh.face_towards(0, far) < 0);
    int far_free = -1;
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(far, f) == kNoTet) far_free = f;
    }
    mesh.glue(0, free_face, far, far_free);
    CHECK(find_mesh_inconsistency(mesh).find("do not share") != std::string::npos);
  }
  SECTION("a detached interior face whose twin still exists") {
    Index t = 0;
    int f = 0;
    while (mesh.neighbour(t, f) == kNoTet) ++f;
    mesh.detach(t, f);
    CHECK(find_mesh_inconsistency(mesh).find("is free but") != std::string::npos);
    mesh.rebuild_adjacency();
    CHECK(find_mesh_inconsistency(mesh).empty());
  }
  SECTION("a tet using a removed vertex") {
    mesh.remove_vertex(7);
    CHECK(find_mesh_inconsistency(mesh).find("removed or missing vertex 7") != std::string::npos);
  }
}

TEST_CASE("tetmesh: surface marks live on both sides of a face", "[tetmesh]") {
  Mesh mesh = from_tet_mesh(test::cube_tets());
  int f = 0;
  while (mesh.neighbour(0, f) == kNoTet) ++f;
  const Index u = mesh.neighbour(0, f);
  const int back = mesh.face_towards(u, 0);
  const std::vector<std::uint32_t> ids = {7, 3, 7};
  mesh.set_surface_ids(0, f, ids);

  CHECK(find_mesh_inconsistency(mesh).empty());
  const auto seen = mesh.surface_ids(u, back);
  CHECK(std::vector<std::uint32_t>(seen.begin(), seen.end()) == std::vector<std::uint32_t>{3, 7});
  for (const Index v : mesh.face_vertices(0, f)) CHECK(mesh.has_flag(v, kOnSurface));

  SECTION("a mark on one side only is caught") {
    mesh.detach(0, f);
    mesh.set_surface_ids(0, f, std::vector<std::uint32_t>{5});
    mesh.glue(0, f, u, back);
    CHECK(find_mesh_inconsistency(mesh).find("different surface marks") != std::string::npos);
  }
  SECTION("connect copies a one-sided mark across") {
    mesh.set_surface_ids(0, f, {});  // clears both sides
    CHECK(mesh.surface_ids(u, back).empty());
    mesh.detach(0, f);
    mesh.set_surface_ids(0, f, std::vector<std::uint32_t>{5});
    const std::vector<Index> both = {0, u};
    mesh.connect(both);
    CHECK(mesh.neighbour(0, f) == u);
    CHECK(mesh.surface_handle(u, back) == mesh.surface_handle(0, f));
    CHECK(find_mesh_inconsistency(mesh).empty());
  }
  SECTION("a mark without flagged corners is caught") {
    mesh.set_flags(mesh.face_vertices(0, f)[0], 0);
    CHECK(find_mesh_inconsistency(mesh).find("not flagged on-surface") != std::string::npos);
  }
}

TEST_CASE("tetmesh: split at a rational point, round it, compact", "[tetmesh]") {
  Mesh mesh = from_tet_mesh(test::cube_tets());
  // A point with ninth coordinates: not a double, strictly inside tet 2.
  const Tet& t2 = mesh.tet(2);
  ExactPoint3 sum(mpq_class(0), mpq_class(0), mpq_class(0));
  for (int k = 0; k < 3; ++k) {
    const ExactPoint3 corner = mesh.position(t2[k]).to_exact();
    sum = ExactPoint3(sum.x + corner.x, sum.y + corner.y, sum.z + corner.z);
  }
  const ExactPoint3 face_centre(sum.x / 3, sum.y / 3, sum.z / 3);
  const ExactPoint3 apex = mesh.position(t2[3]).to_exact();
  const ExactPoint3 inside((face_centre.x * 2 + apex.x) / 3, (face_centre.y * 2 + apex.y) / 3,
                           (face_centre.z * 2 + apex.z) / 3);
  const HybridPoint p = HybridPoint::from_exact(inside);
  REQUIRE(p.is_exact());

  const Index v = split_tet(mesh, 2, p);
  CHECK(mesh.num_tets() == 9);
  CHECK(find_mesh_inconsistency(mesh).empty());
  CHECK(count_free_faces(mesh) == 12);
  CHECK_THROWS_AS(to_tet_mesh(mesh), RunError);

  // Incidence two ways agree, then the rational vertex rounds safely.
  const VertexTets incidence(mesh);
  const auto star = incidence.of(v);
  CHECK(star.size() == 4);
  CHECK(tets_around_vertex(mesh, v, star.front()) == std::vector<Index>(star.begin(), star.end()));
  std::vector<Tet> incident;
  for (const Index t : star) incident.push_back(mesh.tet(t));
  std::vector<HybridPoint> positions;
  for (Index i = 0; i < mesh.vertex_slots(); ++i) positions.push_back(mesh.position(i));
  REQUIRE(try_round_vertex(positions, v, incident));
  mesh.position(v) = positions[v];
  CHECK(find_mesh_inconsistency(mesh).empty());

  // The freed slot of tet 2 was reused; compaction keeps a valid mesh.
  mesh.remove_tet(star.back());
  CHECK(find_mesh_inconsistency(mesh).empty());
  const Compaction maps = mesh.compact();
  CHECK(mesh.tet_slots() == 8);
  CHECK(find_mesh_inconsistency(mesh).empty());
  const TetMesh out = to_tet_mesh(mesh);
  CHECK(out.tets.size() == 8);
  CHECK(maps.tet_map[star.back()] == kNoTet);
}

TEST_CASE("tetmesh: the walks around an edge find what the vertex star does", "[tetmesh]") {
  // A background mesh of a cube: interior edges with full rings, and edges
  // on the box whose tets form an open fan.
  const TriangleSoup cube = test::cube_soup();
  const DerivedParameters derived = derive_parameters({}, cube);
  const Mesh mesh =
      build_background_mesh(cube, spatial::AabbTree(cube), background_parameters(derived, 0)).mesh;
  std::size_t edges = 0, fans = 0;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const Tet corners = mesh.tet(t);
    for (int x = 0; x < 4; ++x)
      for (int y = x + 1; y < 4; ++y) {
        const Index a = corners[x], b = corners[y];
        std::vector<Index> expected = tets_around_vertex(mesh, a, t);
        std::erase_if(expected, [&](Index u) { return mesh.corner_of(u, b) < 0; });
        const std::vector<Index> ring = tets_around_edge(mesh, a, b, t);
        REQUIRE(ring == expected);
        // From the last tet of a's star, the walk finds one of the ring.
        const Index far_seed = tets_around_vertex(mesh, a, t).back();
        REQUIRE(std::binary_search(ring.begin(), ring.end(), tet_with_edge(mesh, a, b, far_seed)));
        ++edges;
        for (Index u : ring)
          for (int f = 0; f < 4; ++f)
            fans += mesh.neighbour(u, f) == kNoTet && mesh.tet(u)[f] != a && mesh.tet(u)[f] != b;
      }
  }
  CHECK(edges > 1000);
  CHECK(fans > 0);  // some edges lie on the box
  // A vertex outside a's star shares no tet with it.
  const Tet first = mesh.tet(0);
  Index not_neighbour = kNoTet;
  const std::vector<Index> star = tets_around_vertex(mesh, first[0], 0);
  for (Index v = 0; v < mesh.vertex_slots() && not_neighbour == kNoTet; ++v) {
    if (std::none_of(star.begin(), star.end(), [&](Index u) { return mesh.corner_of(u, v) >= 0; }))
      not_neighbour = v;
  }
  REQUIRE(not_neighbour != kNoTet);
  CHECK(tet_with_edge(mesh, first[0], not_neighbour, 0) == kNoTet);
  CHECK_THROWS_AS(tet_with_edge(mesh, Index(mesh.vertex_slots() + 5), first[0], 0), UsageError);
  CHECK_THROWS_AS(tets_around_edge(mesh, mesh.tet(0)[0], Index(mesh.vertex_slots() + 5), 0), UsageError);
}

TEST_CASE("tetmesh: bad input to the mesh is refused", "[tetmesh]") {
  Mesh mesh;
  const Index a = mesh.add_vertex(Vec3d(0, 0, 0));
  mesh.add_vertex(Vec3d(1, 0, 0));
  CHECK_THROWS_AS(mesh.add_tet({a, a, 1, 0}), UsageError);
  CHECK_THROWS_AS(mesh.add_tet({0, 1, 2, 3}), UsageError);

  TetMesh three_on_a_face = two_tets(false);
  three_on_a_face.positions.emplace_back(0.3, 0.3, 2.0);
  three_on_a_face.tets.push_back({0, 1, 2, 5});
  CHECK_THROWS_AS(from_tet_mesh(three_on_a_face), UsageError);
  TetMesh out_of_range = two_tets(false);
  out_of_range.tets[0][0] = 9;
  CHECK_THROWS_AS(from_tet_mesh(out_of_range), UsageError);
}
