// Hostile volume files: each must end in exit code 2 from format-convert,
// with a message naming the file and the problem, and no output file.

#include "file_checks.h"
#include "test_support.h"

#include <mr/core/errors.h>
#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <cstring>
#include <random>

using namespace mr;

namespace {

const std::string kHeader41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const std::string kHeader22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
const std::string kNodes41 = "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";
const std::string kNodes22 = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";

// A valid binary file written by our writer, cut at a fraction of the way
// into the named section's data.
std::vector<char> cut_binary(const TetMesh& mesh, const std::string& version, const std::string& section) {
  test::TempDir dir("bad_volume_src");
  io::WriteOptions options;
  options.msh_version = version;
  io::write_volume(io::make_default_registry(), mesh, dir / "ok.msh", options);
  std::vector<char> bytes = test::read_bytes(dir / "ok.msh");
  const std::string text(bytes.begin(), bytes.end());
  const std::size_t begin = text.find(section), end = text.find("$End" + section.substr(1));
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  bytes.resize(begin + (end - begin) / 2);
  return bytes;
}

}  // namespace

TEST_CASE("MSH 4.1 element naming an undefined node", "[tet_io][bad_input]") {
  test::expect_text_rejected("missing_node.msh",
                             kHeader41 + kNodes41 + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 99\n$EndElements\n",
                             "node tag 99", "out.mesh");
}

TEST_CASE("MSH 2.2 element naming an undefined node", "[tet_io][bad_input]") {
  test::expect_text_rejected("missing_node22.msh",
                             kHeader22 + kNodes22 + "$Elements\n1\n1 4 2 1 1 1 2 3 5\n$EndElements\n",
                             "node tag 5", "out.mesh");
}

TEST_CASE("MSH ASCII truncated in $Nodes and in $Elements", "[tet_io][bad_input]") {
  test::expect_text_rejected("cut_nodes41.msh",
                             kHeader41 + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0", "truncated",
                             "out.mesh");
  test::expect_text_rejected("cut_nodes22.msh", kHeader22 + "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0",
                             "truncated", "out.mesh");
  test::expect_text_rejected("cut_elements41.msh",
                             kHeader41 + kNodes41 + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3", "truncated",
                             "out.mesh");
  test::expect_text_rejected("cut_elements22.msh", kHeader22 + kNodes22 + "$Elements\n1\n1 4 2 1 1 1 2 3",
                             "unexpected end of file", "out.mesh");
}

TEST_CASE("MSH binary truncated in $Nodes and in $Elements", "[tet_io][bad_input]") {
  test::TempDir dir("bad_volume_binary");
  const TetMesh cube = test::cube_tets();
  for (const std::string version : {"4.1", "2.2"})
    for (const std::string section : {"$Nodes", "$Elements"}) {
      INFO(version << " " << section);
      const std::filesystem::path path = dir / ("cut" + version + section.substr(1) + ".msh");
      test::write_bytes(path, cut_binary(cube, version, section));
      test::expect_rejected(path, "truncated", "out.mesh");
      std::filesystem::remove(path);
    }
}

TEST_CASE("MSH ASCII with 2^31 nodes declared in a 1 KB file fails fast", "[tet_io][bad_input]") {
  const std::string huge = "2147483648";
  std::string ascii41 =
      kHeader41 + "$Nodes\n1 " + huge + " 1 " + huge + "\n3 1 0 " + huge + "\n1\n0 0 0\n$EndNodes\n";
  ascii41.resize(1024, '\n');
  test::expect_text_rejected("huge41.msh", ascii41, "$Nodes declares 2147483648 entries", "out.mesh");
  std::string ascii22 = kHeader22 + "$Nodes\n" + huge + "\n1 0 0 0\n$EndNodes\n";
  ascii22.resize(1024, '\n');
  test::expect_text_rejected("huge22.msh", ascii22, "$Nodes declares 2147483648 entries", "out.mesh");
}

TEST_CASE("MSH binary with 2^31 nodes declared in a 1 KB file fails fast", "[tet_io][bad_input]") {
  const std::int32_t one = 1;
  std::string binary41 = "$MeshFormat\n4.1 1 8\n";
  binary41.append(reinterpret_cast<const char*>(&one), 4).append("\n$EndMeshFormat\n$Nodes\n");
  for (std::uint64_t v : {std::uint64_t(1), std::uint64_t(1) << 31, std::uint64_t(1), std::uint64_t(1) << 31})
    binary41.append(reinterpret_cast<const char*>(&v), 8);
  binary41.resize(1024, '\0');
  test::expect_text_rejected("huge41b.msh", binary41, "$Nodes declares 2147483648 entries", "out.mesh");

  std::string binary22 = "$MeshFormat\n2.2 1 8\n";
  binary22.append(reinterpret_cast<const char*>(&one), 4).append("\n$EndMeshFormat\n$Nodes\n2147483648\n");
  binary22.resize(1024, '\0');
  test::expect_text_rejected("huge22b.msh", binary22, "$Nodes declares 2147483648 entries", "out.mesh");
}

TEST_CASE("MSH with huge element and entity counts fails fast", "[tet_io][bad_input]") {
  test::expect_text_rejected(
      "huge_elements.msh",
      kHeader41 + kNodes41 +
          "$Elements\n1 4294967296 1 4294967296\n3 1 4 4294967296\n1 1 2 3 4\n$EndElements\n",
      "4294967296", "out.mesh");
  test::expect_text_rejected("huge_entities.msh",
                             kHeader41 + "$Entities\n0 0 0 1000000000\n1 0 0 0 1 1 1 0 0\n$EndEntities\n",
                             "1000000000", "out.mesh");
  test::expect_text_rejected(
      "huge_tags.msh", kHeader22 + kNodes22 + "$Elements\n1\n1 4 2000000000 1 1 1 2 3 4\n$EndElements\n",
      "expected an integer for element tag", "out.mesh");
}

TEST_CASE("MSH with a missing $EndNodes", "[tet_io][bad_input]") {
  test::expect_text_rejected("no_end_nodes.msh",
                             kHeader22 +
                                 "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
                                 "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n",
                             "expected $EndNodes", "out.mesh");
}

TEST_CASE("MSH with NaN coordinates", "[tet_io][bad_input]") {
  test::expect_text_rejected("nan.msh",
                             kHeader22 +
                                 "$Nodes\n4\n1 0 0 0\n2 nan 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
                                 "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n",
                             "non-finite", "out.mesh");
}

TEST_CASE("MSH of an unsupported version", "[tet_io][bad_input]") {
  test::expect_text_rejected("v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n" + kNodes22,
                             "unsupported MSH version 3.0", "out.mesh");
  test::expect_text_rejected("v40.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n" + kNodes22,
                             "unsupported MSH version 4", "out.mesh");
}

TEST_CASE("MSH with an element type of unknown size", "[tet_io][bad_input]") {
  test::expect_text_rejected("type99.msh",
                             kHeader22 + kNodes22 + "$Elements\n1\n1 99 2 1 1 1 2 3 4\n$EndElements\n",
                             "unsupported element type 99", "out.mesh");
  test::expect_text_rejected("polygon.msh",
                             kHeader41 + kNodes41 + "$Elements\n1 1 1 1\n2 1 34 1\n1 1 2 3\n$EndElements\n",
                             "unsupported element type 34", "out.mesh");
}

TEST_CASE("MSH with a node tag defined twice", "[tet_io][bad_input]") {
  test::expect_text_rejected("dup.msh", kHeader22 + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n",
                             "node tag 1 is defined twice", "out.mesh");
  test::expect_text_rejected("dup_sparse.msh",
                             kHeader22 + "$Nodes\n3\n1 0 0 0\n900000000000 1 0 0\n1 1 0 0\n$EndNodes\n",
                             "node tag 1 is defined twice", "out.mesh");
}

TEST_CASE("MSH with a section that never ends", "[tet_io][bad_input]") {
  test::expect_text_rejected("unclosed.msh", kHeader22 + kNodes22 + "$Comments\nno end\n",
                             "has no $EndComments", "out.mesh");
}

TEST_CASE("Medit with a vertex index of 0 or past the count", "[tet_io][bad_input]") {
  const std::string vertices =
      "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
  test::expect_text_rejected("zero.mesh", vertices + "Tetrahedra\n1\n0 2 3 4 1\nEnd\n", "refers to vertex 0",
                             "out.mesh");
  test::expect_text_rejected("past.mesh", vertices + "Triangles\n1\n1 2 5 1\nEnd\n", "refers to vertex 5",
                             "out.mesh");
}

TEST_CASE("Medit with huge counts fails fast", "[tet_io][bad_input]") {
  test::expect_text_rejected("huge.mesh",
                             "MeshVersionFormatted 2\nDimension 3\nVertices\n2147483648\n0 0 0 0\nEnd\n",
                             "2147483648", "out.mesh");
  test::expect_text_rejected(
      "huge_tets.mesh",
      "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\nTetrahedra\n99999999999\n1 1 1 1 0\n",
      "99999999999", "out.mesh");
  test::expect_text_rejected("huge_edges.mesh",
                             "MeshVersionFormatted 2\nDimension 3\nEdges\n4000000000\n1 2 0\n", "4000000000",
                             "out.mesh");
}

TEST_CASE("Medit with an unknown keyword or a bad number", "[tet_io][bad_input]") {
  test::expect_text_rejected("keyword.mesh", "MeshVersionFormatted 2\nDimension 3\nBananas\n1\n",
                             "unknown keyword 'Bananas'", "out.mesh");
  test::expect_text_rejected("number.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 zero 0 0\n",
                             "found 'zero'", "out.mesh");
}

TEST_CASE("garbage files are rejected as MSH and as Medit", "[tet_io][bad_input]") {
  std::mt19937 rng(12345);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = static_cast<char>(rng());
  test::expect_text_rejected("garbage.msh", garbage, "not a Gmsh MSH file", "out.mesh");
  test::expect_text_rejected("garbage.mesh", garbage, "not a Medit mesh file", "out.mesh");
  test::expect_text_rejected("text.msh", "hello world\n", "not a Gmsh MSH file", "out.mesh");
}

TEST_CASE("random corruptions of valid files never crash", "[tet_io][bad_input]") {
  test::TempDir dir("bad_volume_fuzz");
  const io::Registry registry = io::make_default_registry();
  TetMesh cube = test::cube_tets();
  cube.faces = {{0, 2, 1}};
  cube.face_labels = {3};
  std::mt19937 rng(7);
  const char* names[] = {"a.msh", "b.msh", "c.msh", "d.msh", "e.mesh"};
  for (int variant = 0; variant < 5; ++variant) {
    io::WriteOptions options;
    options.binary = variant % 2 == 1;
    options.msh_version = variant < 2 ? "4.1" : "2.2";
    const std::filesystem::path path = dir / names[variant];
    io::write_volume(registry, cube, path, options);
    const std::vector<char> original = test::read_bytes(path);
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<char> bytes = original;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) bytes[rng() % bytes.size()] = static_cast<char>(rng());
      if (trial % 3 == 0) bytes.resize(rng() % bytes.size() + 1);
      test::write_bytes(path, bytes);
      try {
        const TetMesh mesh = io::read_volume(registry, path);
        CHECK(find_tet_mesh_inconsistency(mesh).empty());
      } catch (const InputError& e) {
        CHECK_THAT(std::string(e.what()), Catch::Contains(path.string()));
      }
    }
  }
}
