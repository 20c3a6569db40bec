// Scene files: round trips, every validation error (message names the JSON pointer and the
// problem), mesh references and their hashes, hostile nesting, and the bundled scenes.
#include "engine/io/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/hash.h"
#include "engine/util/limits.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

const std::string kBunny = std::string(STRATA_TEST_DATA) + "/bunny.obj";

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A fresh, empty folder per test, removed afterwards.
class SceneFileDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("strata_scene_" + std::to_string(::getpid()) + "_" +
                                        info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// ---- building documents ------------------------------------------------------------------

std::shared_ptr<Node> makeNode(NodeId id, NodeKind kind, const std::string& name) {
  auto n = std::make_shared<Node>();
  n->id = id;
  n->kind = kind;
  n->name = name;
  return n;
}

// A scene with every node kind, unusual transforms and colours, a hidden node, bounds.
Scene everyKindScene(const std::string& meshPath, const std::string& meshHash) {
  auto root = makeNode(1, NodeKind::Difference, "part");
  root->transform.translate = {0.1, -1.0 / 3.0, 1e-300};
  root->transform.rotateDegrees = {90, -45.5, 1e10};
  root->transform.scale = {-1, 2.5, 0.001};
  root->color = {0.1f, 0.2f, 0.3f};

  auto box = makeNode(2, NodeKind::Box, "block");
  box->params.size = {2, 3.25, 0.7};
  box->color = {0.123456f, 1.0f, 0.0f};
  auto sphere = makeNode(3, NodeKind::Sphere, "ball \"quoted\" ünïcode");
  sphere->params.radius = 0.7;
  sphere->params.segments = 48;
  sphere->visible = false;
  auto cylinder = makeNode(4, NodeKind::Cylinder, "hole");
  cylinder->params.radius = 0.5;
  cylinder->params.height = 3;
  cylinder->transform.rotateDegrees = {0, 90, 0};
  auto cone = makeNode(5, NodeKind::Cone, "cone");
  cone->params.radius = 1;
  cone->params.topRadius = 0.25;
  cone->params.height = 2;
  cone->params.segments = 3;
  auto torus = makeNode(6, NodeKind::Torus, "ring");
  torus->params.majorRadius = 2;
  torus->params.minorRadius = 0.3;
  auto capsule = makeNode(7, NodeKind::Capsule, "pill");
  capsule->params.radius = 0.2;
  capsule->params.height = 1.5;
  auto mesh = makeNode(8, NodeKind::Mesh, "bunny");
  mesh->meshPath = meshPath;
  mesh->meshHash = meshHash;
  mesh->transform.scale = {0.1, 0.1, 0.1};
  auto group = makeNode(9, NodeKind::Union, "group");
  group->children = {sphere, cone, torus};
  auto copy = makeNode(10, NodeKind::Instance, "copy");
  copy->instanceOf = 9;
  copy->transform.translate = {5, 0, 0};
  auto empty = makeNode(11, NodeKind::Intersection, "empty");
  root->children = {box, cylinder, group, capsule, mesh, copy, empty};

  Scene scene;
  scene.root = root;
  scene.settings.resolution = 300;
  scene.settings.margin = 0.125;
  scene.settings.unit = "inch";
  scene.settings.hasBounds = true;
  scene.settings.bounds.min = {-10, -10.5, -1e-3};
  scene.settings.bounds.max = {10, 10, 7};
  return scene;
}

void expectSameTree(const NodePtr& a, const NodePtr& b, const std::string& where) {
  ASSERT_TRUE(a && b) << where;
  SCOPED_TRACE(where + " (node " + std::to_string(a->id) + ")");
  EXPECT_EQ(a->id, b->id);
  EXPECT_EQ(a->name, b->name);
  EXPECT_EQ(a->kind, b->kind);
  EXPECT_TRUE(a->transform == b->transform);
  EXPECT_EQ(a->color.r, b->color.r);
  EXPECT_EQ(a->color.g, b->color.g);
  EXPECT_EQ(a->color.b, b->color.b);
  EXPECT_EQ(a->visible, b->visible);
  if (isPrimitive(a->kind)) {
    EXPECT_TRUE(a->params == b->params);
  }
  EXPECT_EQ(a->meshPath, b->meshPath);
  EXPECT_EQ(a->meshHash, b->meshHash);
  EXPECT_EQ(a->instanceOf, b->instanceOf);
  ASSERT_EQ(a->children.size(), b->children.size());
  for (size_t i = 0; i < a->children.size(); ++i)
    expectSameTree(a->children[i], b->children[i], where + "/" + std::to_string(i));
}

// ---- validation helpers ------------------------------------------------------------------

// A complete document around `root` (JSON text), with `extra` top-level members before it.
std::string doc(const std::string& root, const std::string& extra = "") {
  return R"({"format": "strata-scene", "version": 1, )" + extra + R"("root": )" + root + "}";
}

// Parses `text`, expecting a strata::Error whose message contains every one of `parts`.
void expectError(const std::string& text, const std::vector<std::string>& parts,
                 const std::string& baseDir = ".") {
  try {
    parseScene(text, "test.strata.json", baseDir);
    ADD_FAILURE() << "no error for: " << text.substr(0, 300);
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_EQ(message.rfind("test.strata.json: ", 0), 0u) << message;
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos)
          << "message: " << message << "\nexpected to contain: " << part;
  }
}

std::string nestedUnions(int levels, const std::string& leaf, NodeId firstId = 1) {
  std::string text;
  for (int i = 0; i < levels; ++i)
    text += R"({"id": )" + std::to_string(firstId + i) + R"(, "type": "union", "children": [)";
  text += leaf;
  for (int i = 0; i < levels; ++i) text += "]}";
  return text;
}

// ---- round trip ----------------------------------------------------------------------------

TEST_F(SceneFileDir, SceneFileRoundTripKeepsEverything) {
  fs::create_directories(dir_ / "meshes");
  fs::copy_file(kBunny, dir_ / "meshes" / "bunny.obj");
  Scene original = everyKindScene("meshes/bunny.obj", hashFile(kBunny));
  std::string path = (dir_ / "part.strata.json").string();
  saveScene(original, path);
  EXPECT_TRUE(temporaryFilesOf(path).empty());

  SceneLoadReport report;
  Scene loaded = loadScene(path, &report);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  expectSameTree(original.root, loaded.root, "/root");
  EXPECT_EQ(loaded.settings.resolution, 300);
  EXPECT_EQ(loaded.settings.margin, 0.125);
  EXPECT_EQ(loaded.settings.unit, "inch");
  EXPECT_TRUE(loaded.settings.hasBounds);
  EXPECT_EQ(loaded.settings.bounds.min, original.settings.bounds.min);
  EXPECT_EQ(loaded.settings.bounds.max, original.settings.bounds.max);

  NodePtr bunny = findNode(loaded.root, 8);
  ASSERT_TRUE(bunny && bunny->mesh);
  EXPECT_EQ(bunny->mesh->triangles.size(), 3674u);

  // Saving what was loaded reproduces the file byte for byte.
  EXPECT_EQ(sceneToJson(loaded), readText(path));
}

TEST(SceneFileWrite, OutputIsStableAndReadable) {
  auto box = makeNode(7, NodeKind::Box, "b");
  box->color = {0.8f, 0.8f, 0.8f};
  Scene scene;
  scene.root = box;
  std::string text = sceneToJson(scene);
  // Fixed key order, two-space indentation, defaults written, floats in their shortest form.
  EXPECT_LT(text.find("\"format\""), text.find("\"version\""));
  EXPECT_LT(text.find("\"version\""), text.find("\"unit\""));
  EXPECT_LT(text.find("\"settings\""), text.find("\"root\""));
  EXPECT_NE(text.find("\n  \"root\": {\n    \"id\": 7,"), std::string::npos) << text;
  EXPECT_NE(text.find("\"translate\""), std::string::npos);
  EXPECT_NE(text.find("\"scale\""), std::string::npos);
  EXPECT_NE(text.find("0.8,"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.800000"), std::string::npos) << text;
  EXPECT_EQ(text.find("\"bounds\""), std::string::npos);
  EXPECT_EQ(text, sceneToJson(parseScene(text, "t", ".")));
}

TEST(SceneFileWrite, RefusesWhatCannotBeRead) {
  Scene scene;
  EXPECT_THROW(sceneToJson(scene), Error);  // no root
  auto box = makeNode(1, NodeKind::Box, "b");
  box->params.size.x = std::nan("");
  scene.root = box;
  try {
    sceneToJson(scene);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("node 1"), std::string::npos) << e.what();
  }
  auto named = makeNode(1, NodeKind::Box, std::string("bad \xff utf-8"));
  scene.root = named;
  EXPECT_THROW(sceneToJson(scene), Error);
}

TEST_F(SceneFileDir, SceneFileSaveErrorsNameThePath) {
  Scene scene;
  scene.root = makeNode(1, NodeKind::Sphere, "s");
  std::string path = (dir_ / "missing-folder" / "x.strata.json").string();
  try {
    saveScene(scene, path);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  // Overwriting an existing file replaces it.
  std::string good = (dir_ / "x.strata.json").string();
  writeText(good, "old");
  saveScene(scene, good);
  EXPECT_EQ(readText(good), sceneToJson(scene));
}

TEST_F(SceneFileDir, SceneFileLoadErrorsNameThePath) {
  std::string path = (dir_ / "absent.strata.json").string();
  try {
    loadScene(path);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// ---- validation ----------------------------------------------------------------------------

TEST(SceneFileValidation, SpecExampleMessage) {
  std::string text = doc(R"({"id": 1, "type": "union", "children": [
      {"id": 2, "type": "box"}, {"id": 3, "type": "sphere", "radius": -2}]})");
  try {
    parseScene(text, "demo.strata.json", ".");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "demo.strata.json: /root/children/1/radius: expected a positive number, got -2");
  }
}

TEST(SceneFileValidation, InvalidJsonReportsLineAndColumn) {
  expectError("{\n  \"format\": \"strata-scene\",\n  \"version\": 1,}\n",
              {"line 3, column 16", "invalid JSON"});
  expectError("{\"format\":\n  tru}", {"line 2, column 6", "invalid JSON", "invalid literal"});
  expectError("", {"line 1, column 1", "invalid JSON"});
  expectError(doc("{\"id\": 1, \"type\": \"box\", \"name\": \"unterminated}"), {"invalid JSON"});
  expectError(doc(R"({"id": 1, "type": "sphere", "radius": 1e999})"),
              {"line 1, column 88", "invalid JSON", "number overflow", "1e999"});
  expectError(doc(R"({"id": 1, "type": "box"})") + " trailing", {"invalid JSON"});
}

TEST(SceneFileValidation, FormatAndVersion) {
  expectError("[1, 2]", {"expected a JSON object at the top level"});
  expectError(R"({"version": 1, "root": {"id": 1, "type": "box"}})",
              {"/format: missing required field"});
  expectError(R"({"format": "obj", "version": 1})", {"/format: expected \"strata-scene\""});
  expectError(R"({"format": "strata-scene", "root": {"id": 1, "type": "box"}})",
              {"/version: missing required field"});
  expectError(R"({"format": "strata-scene", "version": 6})",
              {"/version: version 6 is newer than this build of Strata reads (5)"});
  expectError(R"({"format": "strata-scene", "version": 99999999999999999999})",
              {"/version: expected an integer"});
  expectError(R"({"format": "strata-scene", "version": "1"})",
              {"/version: expected an integer, got \"1\""});
  expectError(R"({"format": "strata-scene", "version": 0})", {"/version: unsupported version 0"});
  expectError(R"({"format": "strata-scene", "version": 1})", {"/root: missing required field"});
}

TEST(SceneFileValidation, UnknownFieldsAnywhere) {
  expectError(doc(R"({"id": 1, "type": "box"})", R"("colour": 1, )"), {"/colour: unknown field"});
  expectError(doc(R"({"id": 1, "type": "box"})", R"("settings": {"quality": 3}, )"),
              {"/settings/quality: unknown field \"quality\""});
  expectError(doc(R"({"id": 1, "type": "box"})",
                  R"("settings": {"bounds": {"min": [0,0,0], "max": [1,1,1], "mid": 1}}, )"),
              {"/settings/bounds/mid: unknown field"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 2, "type": "box",
                      "sise": [1, 1, 1]}]})"),
              {"/root/children/0/sise: unknown field \"sise\""});
  expectError(doc(R"({"id": 1, "type": "box", "transform": {"skew": [0, 0, 0]}})"),
              {"/root/transform/skew: unknown field"});
  expectError(doc(R"({"id": 1, "type": "box", "a/b~c": 0})"), {"/root/a~1b~0c: unknown field"});
}

TEST(SceneFileValidation, DuplicateKeys) {
  expectError(doc(R"({"id": 1, "type": "box", "name": "a", "name": "b"})"),
              {"/root/name: duplicate key"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 2, "type": "box"},
                      {"id": 3, "type": "box", "transform": {"scale": [1,1,1], "scale": [2,2,2]}}]})"),
              {"/root/children/1/transform/scale: duplicate key"});
}

TEST(SceneFileValidation, WrongTypes) {
  expectError(doc(R"({"id": 1, "type": "box", "name": 5})"),
              {"/root/name: expected a string, got 5"});
  expectError(doc(R"({"id": 1, "type": "box", "visible": "yes"})"),
              {"/root/visible: expected true or false, got \"yes\""});
  expectError(doc(R"({"id": 1, "type": "union", "children": {}})"),
              {"/root/children: expected an array of nodes, got an object"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [3]})"),
              {"/root/children/0: expected a node object, got 3"});
  expectError(doc(R"({"id": 1, "type": "box", "transform": {"translate": [1, 2]}})"),
              {"/root/transform/translate: expected an array of 3 numbers, got an array of 2"});
  expectError(doc(R"({"id": 1, "type": "box", "transform": {"rotate": [0, "a", 0]}})"),
              {"/root/transform/rotate/1: expected a number, got \"a\""});
  expectError(doc(R"({"id": 1, "type": "box", "transform": [0, 0, 0]})"),
              {"/root/transform: expected an object"});
  expectError(doc(R"({"id": 1, "type": "box", "size": 2})"),
              {"/root/size: expected an array of 3 numbers, got 2"});
  expectError(doc(R"({"id": 1, "type": "sphere", "radius": null})"),
              {"/root/radius: expected a positive number, got null"});
  expectError(doc(R"({"id": 1, "type": "sphere", "segments": 12.5})"),
              {"/root/segments: expected 0 (automatic) or an integer from 3 to"});
  expectError(doc(R"({"id": 1, "type": 4})"), {"/root/type: expected a string, got 4"});
  expectError(doc(R"({"id": 1, "type": "box"})", R"("unit": 5, )"), {"/unit: expected a string"});
  expectError(doc(R"({"id": 1, "type": "box"})", R"("unit": "", )"),
              {"/unit: expected a non-empty string"});
  expectError(doc(R"({"id": 1, "type": "box"})", R"("settings": [], )"),
              {"/settings: expected an object"});
}

TEST(SceneFileValidation, ValuesOutOfRange) {
  auto leaf = [](const std::string& fields) {
    return doc(R"({"id": 1, "type": "union", "children": [)" + fields + "]}");
  };
  expectError(leaf(R"({"id": 2, "type": "box", "size": [1, 0, 1]})"),
              {"/root/children/0/size/1: expected a positive number, got 0"});
  expectError(leaf(R"({"id": 2, "type": "cylinder", "height": -1})"),
              {"/root/children/0/height: expected a positive number, got -1"});
  expectError(leaf(R"({"id": 2, "type": "cone", "topRadius": -0.5})"),
              {"/root/children/0/topRadius: expected a number >= 0, got -0.5"});
  expectError(leaf(R"({"id": 2, "type": "torus", "majorRadius": 1, "minorRadius": 1})"),
              {"/root/children/0/minorRadius: minorRadius (1) must be smaller than majorRadius"});
  expectError(leaf(R"({"id": 2, "type": "torus", "majorRadius": 0.2})"),
              {"/root/children/0/majorRadius: minorRadius (0.25) must be smaller"});
  expectError(leaf(R"({"id": 2, "type": "capsule", "radius": 0})"),
              {"/root/children/0/radius: expected a positive number, got 0"});
  expectError(leaf(R"({"id": 2, "type": "sphere", "segments": 2})"),
              {"/root/children/0/segments: expected 0 (automatic) or an integer from 3", "got 2"});
  expectError(leaf(R"({"id": 2, "type": "sphere", "segments": 100000})"),
              {"/root/children/0/segments:", "got 100000"});
  expectError(leaf(R"({"id": 2, "type": "box", "transform": {"scale": [1, 1, 0]}})"),
              {"/root/children/0/transform/scale/2: expected a nonzero number, got 0"});
  expectError(leaf(R"({"id": 2, "type": "box", "color": [0.5, 1.5, 0]})"),
              {"/root/children/0/color/1: expected a number from 0 to 1, got 1.5"});
  expectError(leaf(R"({"id": 2, "type": "box", "color": [0.5, 0.5, -0.1]})"),
              {"/root/children/0/color/2: expected a number from 0 to 1"});
  std::string root = R"({"id": 1, "type": "box"})";
  expectError(doc(root, R"("settings": {"resolution": 4}, )"),
              {"/settings/resolution: expected an integer from 8 to 16384, got 4"});
  expectError(doc(root, R"("settings": {"resolution": 16385}, )"), {"/settings/resolution:"});
  expectError(doc(root, R"("settings": {"resolution": 256.5}, )"),
              {"/settings/resolution: expected an integer", "got 256.5"});
  expectError(doc(root, R"("settings": {"margin": 10.5}, )"),
              {"/settings/margin: expected a number from 0 to 10, got 10.5"});
  expectError(doc(root, R"("settings": {"margin": -0.01}, )"), {"/settings/margin:"});
  expectError(doc(root, R"("settings": {"bounds": {"min": [0, 0, 0], "max": [1, 0, 1]}}, )"),
              {"/settings/bounds/max/1: expected a number greater than min (0), got 0"});
  expectError(doc(root, R"("settings": {"bounds": {"min": [0, 0, 0]}}, )"),
              {"/settings/bounds/max: missing required field"});
}

TEST(SceneFileValidation, NodeTypesAndTheirFields) {
  expectError(doc(R"({"id": 1, "type": "blob"})"),
              {"/root/type: unknown node type \"blob\"", "union", "instance"});
  expectError(doc(R"({"id": 1})"), {"/root/type: missing required field"});
  expectError(doc(R"({"id": 1, "type": "union", "radius": 2})"),
              {"/root/radius: field \"radius\" does not apply to a union node"});
  expectError(doc(R"({"id": 1, "type": "difference", "path": "a.obj"})"),
              {"/root/path: field \"path\" does not apply to a difference node"});
  expectError(doc(R"({"id": 1, "type": "box", "radius": 2})"),
              {"/root/radius: field \"radius\" does not apply to a box node"});
  expectError(doc(R"({"id": 1, "type": "mesh", "path": "a.obj", "segments": 8})"),
              {"/root/segments: field \"segments\" does not apply to a mesh node"});
  expectError(doc(R"({"id": 1, "type": "sphere", "children": []})"),
              {"/root/children: a sphere node cannot have children"});
  expectError(doc(R"({"id": 1, "type": "instance", "of": 1, "children": []})"),
              {"/root/children: a instance node cannot have children"});
  expectError(doc(R"({"id": 1, "type": "mesh"})"), {"/root/path: missing required field"});
  expectError(doc(R"({"id": 1, "type": "mesh", "path": ""})"),
              {"/root/path: expected a non-empty string"});
  expectError(doc(R"({"id": 1, "type": "mesh", "path": "a.obj", "hash": "md5:00"})"),
              {"/root/hash: expected \"fnv1a64:\" followed by 16 lowercase hex digits"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 2, "type": "instance"}]})"),
              {"/root/children/0/of: missing required field"});
}

TEST(SceneFileValidation, EmptyOperationsAreAllowed) {
  for (const char* type : {"union", "intersection", "difference"}) {
    Scene scene = parseScene(
        doc(std::string(R"({"id": 1, "type": ")") + type + R"(", "children": []})"), "t", ".");
    EXPECT_TRUE(scene.root->children.empty());
  }
  Scene scene = parseScene(doc(R"({"id": 4, "type": "union"})"), "t", ".");
  EXPECT_EQ(scene.root->id, 4u);
  EXPECT_EQ(scene.settings.resolution, 256);
  EXPECT_EQ(scene.settings.unit, "millimetre");
  EXPECT_FALSE(scene.settings.hasBounds);
}

TEST(SceneFileValidation, Ids) {
  expectError(doc(R"({"type": "box"})"), {"/root/id: missing required field"});
  expectError(doc(R"({"id": 0, "type": "box"})"),
              {"/root/id: expected a positive integer", "got 0"});
  expectError(doc(R"({"id": -3, "type": "box"})"), {"/root/id:", "got -3"});
  expectError(doc(R"({"id": 1.5, "type": "box"})"), {"/root/id:", "got 1.5"});
  expectError(doc(R"({"id": 4294967296, "type": "box"})"), {"/root/id:", "got 4294967296"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 2, "type": "box"},
                      {"id": 2, "type": "sphere"}]})"),
              {"/root/children/1/id: duplicate id 2 (also used by the node at /root/children/0)"});
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 1, "type": "box"}]})"),
              {"/root/children/0/id: duplicate id 1 (also used by the node at /root)"});
}

TEST(SceneFileValidation, Instances) {
  expectError(doc(R"({"id": 1, "type": "union", "children": [
                      {"id": 2, "type": "instance", "of": 99}]})"),
              {"/root/children/0/of: refers to node 99, which does not exist"});
  // Itself.
  expectError(doc(R"({"id": 1, "type": "union", "children": [
                      {"id": 2, "type": "instance", "of": 2}]})"),
              {"/root/children/0/of: instance cycle 2 -> 2"});
  // An ancestor.
  expectError(doc(R"({"id": 1, "type": "union", "children": [{"id": 2, "type": "difference",
                      "children": [{"id": 3, "type": "box"}, {"id": 4, "type": "instance",
                      "of": 1}]}]})"),
              {"/root/children/0/children/1/of: instance cycle 4 -> 1 -> 2 -> 4"});
  // Through another instance: 5 shows group 2, which holds 3 showing group 4, which holds 5.
  expectError(doc(R"({"id": 1, "type": "union", "children": [
                      {"id": 2, "type": "union", "children": [{"id": 3, "type": "instance", "of": 4}]},
                      {"id": 4, "type": "union", "children": [{"id": 5, "type": "instance", "of": 2}]}]})"),
              {"/of: instance cycle", "3 -> 4 -> 5 -> 2 -> 3"});
  // A chain of instances and instances of siblings are fine.
  Scene scene = parseScene(doc(R"({"id": 1, "type": "union", "children": [
                      {"id": 2, "type": "sphere"}, {"id": 3, "type": "instance", "of": 2},
                      {"id": 4, "type": "instance", "of": 3}, {"id": 5, "type": "instance",
                      "of": 6}, {"id": 6, "type": "union", "visible": false, "children": [
                      {"id": 7, "type": "instance", "of": 2}]}]})"),
                           "t", ".");
  EXPECT_EQ(treeDepth(scene.root), 3);  // 1 -> instance 5 -> union 6 -> instance 7 -> sphere
}

TEST(SceneFileValidation, TreeDepth) {
  // kMaxTreeDepth levels are fine, one more is not.
  std::string leaf =
      R"({"id": 100000, "type": "box", "transform": {"translate": [1, 2, 3]}, "color": [1, 1, 1]})";
  EXPECT_NO_THROW(parseScene(doc(nestedUnions(kMaxTreeDepth - 1, leaf)), "t", "."));
  expectError(doc(nestedUnions(kMaxTreeDepth, leaf)),
              {"/children/0: the tree is more than 512 levels deep"});
  // Depth counted through instances: two chains of 300 levels, one instancing the other.
  std::string chainB = nestedUnions(300, R"({"id": 200000, "type": "box"})", 1000);
  std::string chainA = nestedUnions(299, R"({"id": 100000, "type": "instance", "of": 1000})", 1);
  expectError(
      doc(R"({"id": 500000, "type": "union", "children": [)" + chainA + "," + chainB + "]}"),
      {"levels deep counting through instances; the limit is 512"});
}

TEST(SceneFileValidation, InstanceDagIsCheckedInLinearTime) {
  // Level k holds two instances of level k-1: following every instance naively visits 2^60
  // nodes, the check must memoise.
  std::string children = R"({"id": 1, "type": "sphere"})";
  for (int k = 1; k <= 60; ++k) {
    NodeId prev = static_cast<NodeId>(3 * (k - 1) + 1);
    std::string id = std::to_string(3 * k + 1);
    children += R"(, {"id": )" + id + R"(, "type": "union", "visible": false, "children": [)" +
                R"({"id": )" + std::to_string(3 * k - 1) + R"(, "type": "instance", "of": )" +
                std::to_string(prev) + R"(}, {"id": )" + std::to_string(3 * k) +
                R"(, "type": "instance", "of": )" + std::to_string(prev) + "}]}";
  }
  Scene scene = parseScene(
      doc(R"({"id": 100000, "type": "union", "children": [)" + children + "]}"), "t", ".");
  EXPECT_EQ(scene.root->children.size(), 61u);
}

TEST(SceneFileValidation, DeepNestingAttack) {
  const int levels = 1000000;
  std::string attack(levels, '[');
  attack += std::string(levels, ']');
  expectError(attack, {"line 1, column 1041", "nested more than 1040 levels deep"});
  expectError(doc(std::string(levels, '{')), {"nested more than 1040 levels deep"});
  // Brackets inside strings (also after an escaped quote) do not count.
  Scene scene =
      parseScene(doc(R"({"id": 1, "type": "box", "name": ")" + std::string(5000, '[') + R"("})",
                     R"("unit": "\")" + std::string(5000, '{') + R"(", )"),
                 "t", ".");
  EXPECT_EQ(scene.root->name, std::string(5000, '['));
  EXPECT_EQ(scene.settings.unit, "\"" + std::string(5000, '{'));
}

// ---- meshes --------------------------------------------------------------------------------

std::string meshDoc(const std::string& path, const std::string& hashField) {
  return doc(R"({"id": 1, "type": "union", "children": [
      {"id": 2, "type": "box"},
      {"id": 3, "name": "bunny", "type": "mesh", "path": ")" +
             path + "\"" + hashField + R"(},
      {"id": 4, "name": "again", "type": "mesh", "path": ")" +
             path + "\"" + hashField + "}]}");
}

TEST_F(SceneFileDir, SceneFileMeshRelativePathAndHash) {
  fs::create_directories(dir_ / "scenes");
  fs::create_directories(dir_ / "meshes");
  fs::copy_file(kBunny, dir_ / "meshes" / "bunny.obj");
  std::string hash = hashFile(kBunny);
  EXPECT_EQ(hash.rfind("fnv1a64:", 0), 0u);
  EXPECT_EQ(hash.size(), 24u);
  writeText(dir_ / "scenes" / "s.strata.json",
            meshDoc("../meshes/bunny.obj", R"(, "hash": ")" + hash + "\""));

  SceneLoadReport report;
  Scene scene = loadScene((dir_ / "scenes" / "s.strata.json").string(), &report);
  EXPECT_TRUE(report.warnings.empty());
  NodePtr a = findNode(scene.root, 3), b = findNode(scene.root, 4);
  ASSERT_TRUE(a && a->mesh && b);
  EXPECT_EQ(a->mesh->triangles.size(), 3674u);
  EXPECT_EQ(a->mesh, b->mesh);  // one file, read once, shared
  EXPECT_EQ(a->meshPath, "../meshes/bunny.obj");
  EXPECT_EQ(a->meshHash, hash);
  EXPECT_NEAR(signedVolume(*a->mesh), 194.288371812, 1e-6);
}

TEST_F(SceneFileDir, SceneFileMeshHashMismatchWarns) {
  fs::copy_file(kBunny, dir_ / "bunny.obj");
  writeText(dir_ / "s.strata.json",
            meshDoc("bunny.obj", R"(, "hash": "fnv1a64:0123456789abcdef")"));
  SceneLoadReport report;
  Scene scene = loadScene((dir_ / "s.strata.json").string(), &report);
  ASSERT_EQ(report.warnings.size(), 2u);
  const std::string& w = report.warnings[0];
  EXPECT_NE(w.find("/root/children/1"), std::string::npos) << w;
  EXPECT_NE(w.find("mesh node 3 \"bunny\""), std::string::npos) << w;
  EXPECT_NE(w.find("\"bunny.obj\" changed since the scene was saved"), std::string::npos) << w;
  EXPECT_NE(w.find("fnv1a64:0123456789abcdef"), std::string::npos) << w;
  // The node now records the hash of what it holds.
  EXPECT_EQ(findNode(scene.root, 3)->meshHash, hashFile(kBunny));
  ASSERT_TRUE(findNode(scene.root, 3)->mesh);
}

// A mesh the artist took although it is open (the editor's import dialog) is marked so in the
// scene (version 5, the mesh's "open"): the file loads without --allow-open on every command and
// in the editor, and saves the mark back; the same file under a mesh not so marked is refused.
TEST_F(SceneFileDir, AnOpenMeshMarkedOpenLoadsAndKeepsTheMark) {
  writeText(dir_ / "open.obj",
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
            "f 3 4 8\nf 3 8 7\nf 4 1 5\n");  // a unit cube short of one triangle
  const std::string marked = doc(R"({"id": 1, "type": "union", "children": [
      {"id": 2, "type": "mesh", "path": "open.obj", "open": true}]})");
  writeText(dir_ / "s.strata.json", marked);
  SceneLoadReport report;
  Scene scene = loadScene((dir_ / "s.strata.json").string(), &report);
  NodePtr leaf = findNode(scene.root, 2);
  ASSERT_TRUE(leaf && leaf->mesh);
  EXPECT_TRUE(leaf->meshOpen);
  EXPECT_EQ(leaf->mesh->triangles.size(), 11u);
  bool said = false;
  for (const std::string& w : report.warnings) said = said || w.find("open") != std::string::npos;
  EXPECT_TRUE(said) << "the load still says it is open";
  const std::string written = sceneToJson(scene);
  EXPECT_NE(written.find("\"open\": true"), std::string::npos) << written;
  EXPECT_NE(written.find("\"version\": 5"), std::string::npos)
      << "older builds refuse it by version";
  Scene again = parseScene(written, "again", dir_.string());
  EXPECT_TRUE(findNode(again.root, 2)->meshOpen);
  // Unmarked, and beside a marked node of the same file: that node is refused, the other loads.
  writeText(dir_ / "u.strata.json", doc(R"({"id": 1, "type": "union", "children": [
      {"id": 2, "type": "mesh", "path": "open.obj"}]})"));
  try {
    loadScene((dir_ / "u.strata.json").string());
    ADD_FAILURE() << "an open mesh not marked open loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("open (boundary) edge"), std::string::npos) << e.what();
  }
  // Taken open no more (the mark cleared): the file says nothing of it and needs no version 5.
  Scene closed = parseScene(written, "again", dir_.string());
  std::const_pointer_cast<Node>(findNode(closed.root, 2))->meshOpen = false;
  const std::string plain = sceneToJson(closed);
  EXPECT_EQ(plain.find("\"open\""), std::string::npos) << plain;
  EXPECT_EQ(plain.find("\"version\": 5"), std::string::npos) << plain;
}

// Names and the unit reach terminals and the editor: control characters in them (an escape
// sequence recoloured a terminal and retitled its window) are replaced by '?', with a warning.
TEST_F(SceneFileDir, ControlCharactersInNamesAndTheUnitAreReplaced) {
  writeText(dir_ / "s.strata.json",
            "{\"format\": \"strata-scene\", \"version\": 1, \"unit\": \"mm\\u0007\", "
            "\"root\": {\"id\": 1, \"type\": \"union\", \"children\": [{\"id\": 2, "
            "\"type\": \"box\", \"name\": \"\\u001b[31mred\\u001b]0;title\\u0007\\u009b1m\"}]}}");
  SceneLoadReport report;
  const Scene scene = loadScene((dir_ / "s.strata.json").string(), &report);
  EXPECT_EQ(findNode(scene.root, 2)->name, "?[31mred?]0;title??1m");
  EXPECT_EQ(scene.settings.unit, "mm?");
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[1].find("/root/children/0/name: 4 control characters replaced"),
            std::string::npos)
      << report.warnings[1];
}

// A file may allow at most 2^24 leaves; one that asks more (older files could ask 2^40) opens,
// held to 2^24, with a warning naming --max-leaves.
TEST_F(SceneFileDir, ALeafLimitAboveTheCeilingIsHeldToIt) {
  writeText(dir_ / "s.strata.json",
            "{\"format\": \"strata-scene\", \"version\": 1, \"settings\": {\"maxLeaves\": "
            "1099511627776}, \"root\": {\"id\": 1, \"type\": \"box\"}}");
  SceneLoadReport report;
  const Scene scene = loadScene((dir_ / "s.strata.json").string(), &report);
  EXPECT_EQ(scene.settings.maxLeaves, uint64_t(kMaxLeavesSetting));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("--max-leaves"), std::string::npos) << report.warnings[0];
}

TEST_F(SceneFileDir, SceneFileMeshWithoutHashWarns) {
  fs::copy_file(kBunny, dir_ / "bunny.obj");
  writeText(dir_ / "s.strata.json", meshDoc("bunny.obj", ""));
  SceneLoadReport report;
  Scene scene = loadScene((dir_ / "s.strata.json").string(), &report);
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[1].find("mesh node 4 \"again\" records no hash"), std::string::npos)
      << report.warnings[1];
  EXPECT_EQ(findNode(scene.root, 4)->meshHash, hashFile(kBunny));
}

TEST_F(SceneFileDir, SceneFileMeshErrorsCarryThePointer) {
  expectError(meshDoc("nowhere.obj", ""), {"/root/children/1/path:", "nowhere.obj"}, dir_.string());
  writeText(dir_ / "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  expectError(meshDoc("broken.obj", ""), {"/root/children/1/path:", "broken.obj"}, dir_.string());
  // Absolute paths ignore the base folder.
  fs::copy_file(kBunny, dir_ / "bunny.obj");
  Scene scene = parseScene(meshDoc((dir_ / "bunny.obj").string(), ""), "t", "/nonexistent");
  EXPECT_TRUE(findNode(scene.root, 3)->mesh);
}

TEST_F(SceneFileDir, SceneFileHashFile) {
  writeText(dir_ / "a.bin", "hello");
  Hasher h;
  h.bytes("hello", 5);
  EXPECT_EQ(hashFile((dir_ / "a.bin").string()), formatContentHash(h.digest()));
  std::string missing = (dir_ / "b.bin").string();
  try {
    hashFile(missing);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos);
  }
}

// ---- bundled scenes -------------------------------------------------------------------------

TEST(SceneFileAssets, DemoSceneLoads) {
  SceneLoadReport report;
  Scene scene = loadScene(std::string(STRATA_ASSETS) + "/scenes/demo.strata.json", &report);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  EXPECT_EQ(scene.settings.resolution, 256);
  EXPECT_EQ(scene.settings.unit, "millimetre");
  EXPECT_GE(treeDepth(scene.root), 3);
  bool hasMesh = false, hasInstance = false;
  std::vector<NodePtr> stack{scene.root};
  while (!stack.empty()) {
    NodePtr n = stack.back();
    stack.pop_back();
    hasMesh |= n->kind == NodeKind::Mesh && n->mesh != nullptr;
    hasInstance |= n->kind == NodeKind::Instance;
    for (const NodePtr& c : n->children) stack.push_back(c);
  }
  EXPECT_TRUE(hasMesh);
  EXPECT_TRUE(hasInstance);
  // The bundled file is in the canonical form sceneToJson writes.
  EXPECT_EQ(sceneToJson(scene), readText(std::string(STRATA_ASSETS) + "/scenes/demo.strata.json"));
}

TEST(SceneFileAssets, TwoSpheresLoads) {
  Scene scene = loadScene(std::string(STRATA_ASSETS) + "/scenes/two_spheres.strata.json");
  ASSERT_EQ(scene.root->kind, NodeKind::Union);
  ASSERT_EQ(scene.root->children.size(), 2u);
  for (const NodePtr& s : scene.root->children) {
    EXPECT_EQ(s->kind, NodeKind::Sphere);
    EXPECT_EQ(s->params.radius, 1.0);
  }
  glm::dvec3 gap =
      scene.root->children[1]->transform.translate - scene.root->children[0]->transform.translate;
  EXPECT_EQ(gap, glm::dvec3(1.0, 0.0, 0.0));  // centres 1 apart: overlapping
}

}  // namespace
}  // namespace strata
