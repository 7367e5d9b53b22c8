// Interoperability with the real gmsh and meshio: gmsh loads what we write,
// we read what gmsh writes, and meshio loads our .vtu. These tools are
// installed by the setup script; a missing tool fails the test loudly. Part
// labels written by tetrahedralize come back as physical groups and names.

#include "test_support.h"

#include "tetrahedralize.h"

#include <mr/io/default_registry.h>
#include <mr/io/mesh_io.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>

using namespace mr;

namespace mr::test::tet_io {
TetMesh kuhn_grid(int n);  // defined in tet_formats_test.cpp
}

namespace {

struct CommandResult {
  int status = -1;
  std::string output;  ///< stdout and stderr together
};

CommandResult run(const std::string& command) {
  CommandResult result;
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe.get())) result.output += buffer.data();
  result.status = pclose(pipe.release());
  return result;
}

std::string quote(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

void require_gmsh() {
  const bool found = std::system("command -v gmsh > /dev/null 2>&1") == 0;
  INFO("gmsh is not on PATH: install it (Debian package gmsh, see the setup script)");
  REQUIRE(found);
}

// A Python 3 that can import meshio (pyenv's python3 may shadow Debian's), or the test fails
// saying what to install.
std::string python_with_meshio() {
  std::string found;
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    if (std::system((std::string(python) + " -c 'import meshio' > /dev/null 2>&1").c_str()) == 0) {
      found = python;
      break;
    }
  }
  INFO("no python3 with meshio found: install python3-meshio (see the setup script)");
  REQUIRE(!found.empty());
  return found;
}

CommandResult gmsh(const std::string& arguments) { return run("gmsh -v 2 -nopopup " + arguments); }

// A 2 x 1 x 0.5 box made by extrusion (no OpenCASCADE needed), coarse.
std::string box_geo(bool physical_groups) {
  std::string geo =
      "lc = 0.35;\n"
      "Point(1) = {0, 0, 0, lc};\n"
      "l[] = Extrude {2, 0, 0} { Point{1}; };\n"
      "s[] = Extrude {0, 1, 0} { Line{l[1]}; };\n"
      "v[] = Extrude {0, 0, 0.5} { Surface{s[1]}; };\n";
  if (physical_groups) geo += "Physical Volume(7) = {v[1]};\nPhysical Surface(3) = {s[1]};\n";
  return geo;
}

double signed_volume(const TetMesh& mesh, const Tet& t) {
  const Vec3d& a = mesh.positions[t[0]];
  return (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).dot(mesh.positions[t[3]] - a) / 6.0;
}

}  // namespace

TEST_CASE("gmsh loads the MSH files we write and re-saves the same mesh", "[gmsh]") {
  require_gmsh();
  test::TempDir dir("gmsh_load");
  const io::Registry registry = io::make_default_registry();
  // Positive labels: gmsh reads a negative physical tag as "reverse the
  // element", and -save_all writes MSH 2.2 without physical tags, so labels
  // come back from elementary tags, which equal our labels when positive.
  TetMesh grid = test::tet_io::kuhn_grid(3);
  for (std::int32_t& label : grid.tet_labels) label += 2;
  for (const std::string version : {"4.1", "2.2"})
    for (const bool binary : {false, true}) {
      const std::string name = "ours" + version + (binary ? "b" : "a");
      INFO(name);
      io::WriteOptions options;
      options.binary = binary;
      options.msh_version = version;
      io::write_volume(registry, grid, dir / (name + ".msh"), options);
      for (const char* format : {"msh22", "msh41"}) {
        const std::filesystem::path resaved = dir / (name + "_" + format + ".msh");
        const CommandResult result =
            gmsh(quote(dir / (name + ".msh")) + " -0 -save_all -o " + quote(resaved) + " -format " + format);
        INFO(format << ": " << result.output);
        REQUIRE(result.status == 0);
        CHECK(result.output.find("Error") == std::string::npos);
        const TetMesh back = io::read_volume(registry, resaved);
        CHECK(back.positions.size() == grid.positions.size());
        CHECK(back.tets.size() == grid.tets.size());
        CHECK(back.faces.size() == grid.faces.size());
        CHECK(test::tet_volume(back) == Approx(test::tet_volume(grid)).epsilon(1e-12));
        CHECK(std::multiset<std::int32_t>(back.tet_labels.begin(), back.tet_labels.end()) ==
              std::multiset<std::int32_t>(grid.tet_labels.begin(), grid.tet_labels.end()));
      }
    }
}

TEST_CASE("we read the MSH files gmsh writes", "[gmsh]") {
  require_gmsh();
  test::TempDir dir("gmsh_write");
  const io::Registry registry = io::make_default_registry();
  struct Case {
    const char* format;
    bool binary;
    bool physical_groups;
    int order;
  };
  const Case cases[] = {{"msh41", true, true, 1},  {"msh41", false, false, 1}, {"msh22", false, true, 1},
                        {"msh22", true, false, 1}, {"msh41", true, true, 2},   {"msh22", false, true, 2}};
  for (const bool physical : {true, false})
    test::write_text(dir / (physical ? "box.geo" : "plain.geo"), box_geo(physical));
  for (const Case& c : cases) {
    const std::filesystem::path out =
        dir / (std::string(c.format) + (c.binary ? "b" : "a") + (c.physical_groups ? "p" : "") +
               std::to_string(c.order) + ".msh");
    INFO(out);
    const CommandResult result = gmsh(quote(dir / (c.physical_groups ? "box.geo" : "plain.geo")) +
                                      " -3 -order " + std::to_string(c.order) + " -format " + c.format +
                                      (c.binary ? " -bin" : "") + " -o " + quote(out));
    INFO(result.output);
    REQUIRE(result.status == 0);
    const TetMesh mesh = io::read_volume(registry, out);
    REQUIRE(mesh.tets.size() > 0);
    CHECK(test::tet_volume(mesh) == Approx(1.0).epsilon(1e-12));
    for (const Tet& t : mesh.tets) REQUIRE(signed_volume(mesh, t) > 0);  // gmsh's orientation is ours
    // Labels: the physical group, or without groups the volume's entity tag.
    CHECK(std::set<std::int32_t>(mesh.tet_labels.begin(), mesh.tet_labels.end()) ==
          std::set<std::int32_t>{c.physical_groups ? 7 : 1});
    if (c.physical_groups) {
      CHECK(mesh.faces.size() > 0);
      CHECK(std::set<std::int32_t>(mesh.face_labels.begin(), mesh.face_labels.end()) ==
            std::set<std::int32_t>{3});
    } else {
      CHECK(mesh.faces.size() > 0);  // all boundary triangles are saved without physical groups
    }
  }
}

TEST_CASE("we read the Medit files gmsh writes, and gmsh reads ours", "[gmsh]") {
  require_gmsh();
  test::TempDir dir("gmsh_medit");
  const io::Registry registry = io::make_default_registry();
  test::write_text(dir / "box.geo", box_geo(true));
  const CommandResult made =
      gmsh(quote(dir / "box.geo") + " -3 -setnumber Mesh.SaveElementTagType 2 -format mesh -o " +
           quote(dir / "box.mesh"));  // references = physical tags
  INFO(made.output);
  REQUIRE(made.status == 0);
  const TetMesh mesh = io::read_volume(registry, dir / "box.mesh");
  REQUIRE(mesh.tets.size() > 0);
  CHECK(test::tet_volume(mesh) == Approx(1.0).epsilon(1e-12));
  CHECK(std::set<std::int32_t>(mesh.tet_labels.begin(), mesh.tet_labels.end()) == std::set<std::int32_t>{7});

  io::write_volume(registry, mesh, dir / "ours.mesh");
  const CommandResult loaded =
      gmsh(quote(dir / "ours.mesh") + " -0 -save_all -format msh41 -o " + quote(dir / "back.msh"));
  INFO(loaded.output);
  REQUIRE(loaded.status == 0);
  const TetMesh back = io::read_volume(registry, dir / "back.msh");
  CHECK(back.tets.size() == mesh.tets.size());
  CHECK(test::tet_volume(back) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("meshio loads the .vtu we write", "[gmsh]") {
  const std::string python = python_with_meshio();
  test::TempDir dir("meshio_vtu");
  const io::Registry registry = io::make_default_registry();
  const TetMesh grid = test::tet_io::kuhn_grid(3);
  std::int64_t label_sum = 0;
  for (std::int32_t label : grid.tet_labels) label_sum += label;
  std::int64_t connectivity_sum = 0;
  for (const Tet& t : grid.tets) connectivity_sum += std::int64_t(t[0]) + t[1] + t[2] + t[3];
  double grid_coordinate_sum = 0;
  for (const Vec3d& p : grid.positions) grid_coordinate_sum += p.sum();
  for (const bool binary : {false, true}) {
    io::WriteOptions options;
    options.binary = binary;
    const std::filesystem::path path = dir / (binary ? "b.vtu" : "a.vtu");
    io::write_volume(registry, grid, path, options);
    const CommandResult result =
        run(python +
            " -c 'import sys, meshio; m = meshio.read(sys.argv[1]); "
            "tets = [c.data for c in m.cells if c.type == \"tetra\"]; "
            "print(len(m.points), sum(len(t) for t in tets), sum(int(t.sum()) for t in tets), "
            "int(sum(a.sum() for a in m.cell_data[\"label\"])), repr(float(m.points.sum())))' " +
            quote(path));
    INFO(result.output);
    REQUIRE(result.status == 0);
    std::istringstream fields(result.output);
    std::size_t points = 0, tets = 0;
    std::int64_t connectivity = 0, labels = 0;
    double coordinate_sum = 0;
    fields >> points >> tets >> connectivity >> labels >> coordinate_sum;
    CHECK(points == grid.positions.size());
    CHECK(tets == grid.tets.size());
    CHECK(connectivity == connectivity_sum);
    CHECK(coordinate_sum == Approx(grid_coordinate_sum).epsilon(1e-12));
    CHECK(labels == label_sum);
  }
}

TEST_CASE("node data (sizing fields) goes both ways between us, meshio and gmsh", "[gmsh][sizing]") {
  // A user makes a sizing field in Python: meshio writes it, we read it;
  // and meshio and gmsh read the node data we write.
  const std::string python = python_with_meshio();
  require_gmsh();
  test::TempDir dir("node_data_interop");
  const io::Registry registry = io::make_default_registry();
  TetMesh grid = test::tet_io::kuhn_grid(2);
  std::vector<double> values;
  for (const Vec3d& p : grid.positions) values.push_back(0.25 + p.x() + 2 * p.y());
  grid.node_fields["values"] = values;
  for (const auto& [format, binary, version] : {std::tuple{"gmsh", false, "4.1"},
                                                {"gmsh", true, "4.1"},
                                                {"gmsh22", false, "2.2"},
                                                {"gmsh22", true, "2.2"}}) {
    CAPTURE(format, binary);
    const std::string tag = std::string(format) + (binary ? "b" : "a");
    const std::filesystem::path ours = dir / (tag + "_ours.msh"), theirs = dir / (tag + "_meshio.msh");
    io::WriteOptions options;
    options.binary = binary;
    options.msh_version = version;
    io::write_volume(registry, grid, ours, options);
    const CommandResult result =
        run(python +
            " -c 'import sys, meshio; m = meshio.read(sys.argv[1]); "
            "print(repr(float(m.point_data[\"values\"].sum()))); "
            "import numpy; tets = numpy.concatenate([c.data for c in m.cells if c.type == \"tetra\"]); "
            "fresh = meshio.Mesh(m.points, [(\"tetra\", tets)], point_data={\"values\": "
            "m.point_data[\"values\"]}); "
            "meshio.write(sys.argv[2], fresh, file_format=sys.argv[3], binary=sys.argv[4] == \"1\")' " +
            quote(ours) + " " + quote(theirs) + " " + format + " " + (binary ? "1" : "0"));
    INFO(result.output);
    REQUIRE(result.status == 0);
    double sum = 0, expected = 0;
    std::istringstream(result.output) >> sum;
    for (const double v : values) expected += v;
    CHECK(sum == Approx(expected).epsilon(1e-12));
    const TetMesh back = io::read_volume(registry, theirs);
    REQUIRE(back.positions.size() == grid.positions.size());
    CHECK(back.node_fields.at("values") == values);
    const CommandResult loaded = gmsh(quote(ours) + " -0 -o " + quote(dir / (tag + "_gmsh.msh")));
    INFO(loaded.output);
    CHECK(loaded.status == 0);
  }
}

TEST_CASE("gmsh and meshio read the part labels tetrahedralize writes", "[gmsh][labels]") {
  require_gmsh();
  const std::string python = python_with_meshio();
  test::TempDir dir("gmsh_labels");
  const io::Registry registry = io::make_default_registry();
  // Two unit boxes touching on x = 1, one OBJ material each.
  TriangleSoup boxes = test::cube_soup();
  TriangleSoup right = test::cube_soup();
  for (Vec3d& p : right.positions) p.x() += 1;
  boxes.face_regions.assign(boxes.triangles.size(), 0);
  right.face_regions.assign(right.triangles.size(), 1);
  boxes.append(right);
  boxes.region_names = {"steel", "rubber"};
  io::write_surface(registry, boxes, dir / "boxes.obj");
  for (const char* out : {"boxes.msh", "boxes.vtu"}) {
    const test::ToolRun made =
        test::run_tool(tools::tetrahedralize,
                       {(dir / "boxes.obj").string(), (dir / out).string(), "--max-passes", "4", "-q"});
    INFO(made.err);
    REQUIRE(made.exit_code == 0);
  }

  // meshio: the physical tag of every tet, and the group names.
  const CommandResult read =
      run(python +
          " -c 'import sys, meshio; m = meshio.read(sys.argv[1]); "
          "tags = sorted(set(int(v) for c, d in zip(m.cells, m.cell_data[\"gmsh:physical\"]) if c.type == "
          "\"tetra\" "
          "for v in d)); "
          "names = sorted((int(v[0]), k) for k, v in m.field_data.items() if int(v[1]) == 3); "
          "v = meshio.read(sys.argv[2]); "
          "print(tags, names, sorted(set(int(x) for a in v.cell_data[\"label\"] for x in a)))' " +
          quote(dir / "boxes.msh") + " " + quote(dir / "boxes.vtu"));
  INFO(read.output);
  REQUIRE(read.status == 0);
  CHECK(read.output.find("[1, 2] [(1, 'steel'), (2, 'rubber')] [1, 2]\n") != std::string::npos);

  // gmsh: loads the mesh and saves it again; the labels come back per box.
  const std::filesystem::path resaved = dir / "resaved.msh";
  const CommandResult result =
      gmsh(quote(dir / "boxes.msh") + " -0 -save_all -o " + quote(resaved) + " -format msh41");
  INFO(result.output);
  REQUIRE(result.status == 0);
  const auto volume_per_label = [](const TetMesh& mesh) {
    std::map<std::int32_t, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      const Tet& c = mesh.tets[t];
      const double x =
          (mesh.positions[c[0]] + mesh.positions[c[1]] + mesh.positions[c[2]] + mesh.positions[c[3]]).x() / 4;
      if (std::abs(x - 1) > 1e-9) CHECK(mesh.tet_labels[t] == (x < 1 ? 1 : 2));  // slivers: by volume
      volumes[mesh.tet_labels[t]] += signed_volume(mesh, c);
    }
    return volumes;
  };
  const std::map<std::int32_t, double> ours = volume_per_label(io::read_volume(registry, dir / "boxes.msh"));
  const std::map<std::int32_t, double> back = volume_per_label(io::read_volume(registry, resaved));
  REQUIRE(ours.size() == 2);
  REQUIRE(back.size() == 2);
  for (std::int32_t label : {1, 2}) {
    CHECK(back.at(label) == Approx(ours.at(label)).epsilon(1e-12));
    // Improvement moves the surface within epsilon (1e-3 of the diagonal, sqrt 6).
    CHECK(ours.at(label) == Approx(1.0).margin(6 * 1e-3 * std::sqrt(6.0)));
  }
}
