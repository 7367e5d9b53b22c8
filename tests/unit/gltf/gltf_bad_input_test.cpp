// Hostile and broken glTF input: every case must end in exit code 2 with a
// message naming the file and the problem, and no output file.

#include "gltf_hand_built.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace mr;
using mr::test::gltf::HandBuilt;
using mr::test::gltf::one_triangle;

namespace {

// Converts `input` to OBJ and checks the refusal; `problem` is a fragment of the expected message.
void expect_refused(const test::TempDir& dir, const std::filesystem::path& input,
                    const std::string& problem) {
  const std::filesystem::path output = dir / "out.obj";
  const test::ToolRun run = test::run_format_convert({input.string(), output.string()});
  INFO(run.err);
  CHECK(run.exit_code == 2);
  CHECK(run.err.find(input.string()) != std::string::npos);
  CHECK(run.err.find(problem) != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(output));
}

void expect_glb_refused(const std::vector<char>& glb, const std::string& problem) {
  test::TempDir dir("gltf_bad");
  test::write_bytes(dir / "bad.glb", glb);
  expect_refused(dir, dir / "bad.glb", problem);
}

void expect_model_refused(const HandBuilt& model, const std::string& problem) {
  expect_glb_refused(model.glb(), problem);
}

}  // namespace

TEST_CASE("the hand-built triangle itself converts (control for the cases below)", "[gltf][bad_input]") {
  test::TempDir dir("gltf_control");
  test::write_bytes(dir / "ok.glb", one_triangle().glb());
  const test::ToolRun run = test::run_format_convert({(dir / "ok.glb").string(), (dir / "out.obj").string()});
  INFO(run.err);
  CHECK(run.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "out.obj"));
}

TEST_CASE("GLB with a wrong magic is refused", "[gltf][bad_input]") {
  std::vector<char> glb = one_triangle().glb();
  glb[3] = 'X';
  expect_glb_refused(glb, "wrong magic");
}

TEST_CASE("GLB whose length field is larger than the file is refused", "[gltf][bad_input]") {
  std::vector<char> glb = one_triangle().glb();
  test::gltf::put_u32(glb, 8, static_cast<std::uint32_t>(glb.size() + 100));
  expect_glb_refused(glb, "length field");
}

TEST_CASE("GLB whose JSON chunk runs past the end is refused", "[gltf][bad_input]") {
  std::vector<char> glb = one_triangle().glb();
  test::gltf::put_u32(glb, 12, static_cast<std::uint32_t>(glb.size()));
  expect_glb_refused(glb, "JSON chunk length");
}

TEST_CASE("GLB whose BIN chunk runs past the end is refused", "[gltf][bad_input]") {
  std::vector<char> glb = one_triangle().glb();
  test::gltf::put_u32(glb, test::gltf::bin_chunk_offset(glb), 0x7FFFFFF0u);
  expect_glb_refused(glb, "BIN chunk length");
}

TEST_CASE("an accessor running past the end of its bufferView is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  SECTION("by its byteOffset") { model.doc["accessors"][0]["byteOffset"] = 8; }
  SECTION("by its count") { model.doc["accessors"][0]["count"] = 4; }
  SECTION("by its stride") { model.doc["bufferViews"][0]["byteStride"] = 16; }
  expect_model_refused(model, "runs past the end of its bufferView");
}

TEST_CASE("a bufferView outside its buffer is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  model.doc["bufferViews"][1]["byteOffset"] = 4096;
  expect_model_refused(model, "lies outside its buffer");
}

TEST_CASE("an index beyond the vertex count is refused", "[gltf][bad_input]") {
  HandBuilt model;
  const int positions = model.add_floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  model.add_mesh({{"POSITION", positions}}, model.add_indices({0, 1, 3}));
  model.set_scene({model.add_node({{"mesh", 0}})});
  expect_model_refused(model, "index 3 in accessor");
}

TEST_CASE("an accessor count of 2^31 in a small file is refused without allocating", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  model.doc["accessors"][0]["count"] = 2147483648ull;
  const std::vector<char> glb = model.glb();
  REQUIRE(glb.size() < 1024);
  expect_glb_refused(glb, "runs past the end of its bufferView");
}

TEST_CASE("a missing external buffer file is refused", "[gltf][bad_input]") {
  test::TempDir dir("gltf_missing_bin");
  test::write_text(dir / "model.gltf", one_triangle().json_text("missing.bin"));
  expect_refused(dir, dir / "model.gltf", "missing.bin");
}

TEST_CASE("invalid JSON is refused", "[gltf][bad_input]") {
  test::TempDir dir("gltf_bad_json");
  SECTION(".gltf") {
    test::write_text(dir / "model.gltf", R"({"asset": {"version": "2.0"}, "meshes": [ )");
    expect_refused(dir, dir / "model.gltf", "JSON");
  }
  SECTION("GLB") {
    test::write_bytes(dir / "model.glb", HandBuilt::pack_glb(R"({"asset": {"version": )", ""));
    expect_refused(dir, dir / "model.glb", "JSON");
  }
}

TEST_CASE("NaN positions are refused", "[gltf][bad_input]") {
  HandBuilt model;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int positions = model.add_floats({0, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3", 3);
  model.doc["accessors"][positions].erase("min");
  model.doc["accessors"][positions].erase("max");
  model.add_mesh({{"POSITION", positions}}, model.add_indices({0, 1, 2}));
  model.set_scene({model.add_node({{"mesh", 0}})});
  expect_model_refused(model, "non-finite");
}

TEST_CASE("a node hierarchy with a cycle is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  model.doc["nodes"][0]["children"] = {1};
  model.add_node({{"children", {0}}});
  expect_model_refused(model, "not a tree");
}

TEST_CASE("references to objects that do not exist are refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  std::string problem;
  SECTION("mesh") {
    model.doc["nodes"][0]["mesh"] = 7;
    problem = "mesh 7";
  }
  SECTION("attribute accessor") {
    model.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
    problem = "accessor 9";
  }
  SECTION("material") {
    model.doc["meshes"][0]["primitives"][0]["material"] = 3;
    problem = "material 3";
  }
  SECTION("scene node") {
    model.doc["scenes"][0]["nodes"] = {5};
    problem = "node 5";
  }
  expect_model_refused(model, problem);
}

TEST_CASE("a sparse accessor is refused with a clear message", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  const int view = model.add_view("\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0", 16);
  model.doc["accessors"][0]["sparse"] = {{"count", 1},
                                         {"indices", {{"bufferView", view}, {"componentType", 5125}}},
                                         {"values", {{"bufferView", view}, {"byteOffset", 4}}}};
  expect_model_refused(model, "sparse");
}

TEST_CASE("absurdly deep JSON nesting is refused without overflowing the stack", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  std::string json = model.json_text();
  json.pop_back();  // the closing brace
  json += ",\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + "}";
  expect_glb_refused(HandBuilt::pack_glb(json, model.bin), "nested");
}

TEST_CASE("a file requiring an unsupported geometry extension is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  model.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  model.doc["extensionsRequired"] = {"EXT_meshopt_compression"};
  expect_model_refused(model, "EXT_meshopt_compression");
}

TEST_CASE("a Draco primitive whose bufferView does not exist is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  model.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 42}, {"attributes", {{"POSITION", 0}}}};
  model.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
#if __has_include(<mr/plugins/draco_codec.h>)  // built with Draco (MR_WITH_DRACO)
  expect_model_refused(model, "bufferView 42");
#else
  expect_model_refused(model, "no Draco support");
#endif
}

TEST_CASE("garbage in a Draco bufferView is refused", "[gltf][bad_input]") {
  HandBuilt model = one_triangle();
  const int view = model.add_view("DRACO garbage that is not a mesh!", 32);
  model.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", view}, {"attributes", {{"POSITION", 0}}}};
  model.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  test::TempDir dir("gltf_bad_draco");
  test::write_bytes(dir / "bad.glb", model.glb());
  const test::ToolRun run =
      test::run_format_convert({(dir / "bad.glb").string(), (dir / "out.obj").string()});
  CHECK(run.exit_code == 2);
  CHECK(run.err.find((dir / "bad.glb").string()) != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "out.obj"));
}
