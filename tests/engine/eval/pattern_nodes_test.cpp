// Pattern nodes (array, circular array, mirror: engine/kinds/patterns.h) through the document,
// the evaluator and scene files: volumes of disjoint copies, where the copies land (a mirrored
// asymmetric part lies on the other side, and only there), the leaf counts that guard a scene's
// size, caching across a changed count, undo, scene files (version 4 only when needed, clear
// errors), and a tiled export that stays watertight with one component per copy.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "engine/document/commands.h"
#include "engine/document/document.h"
#include "engine/document/expansion.h"
#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

NodePtr pattern(NodeKind kind, const PatternParams& params, std::initializer_list<NodePtr> kids) {
  auto node = std::make_shared<Node>(*op(kind, kids));
  node->pattern = params;
  return node;
}

PatternParams arrayOf(glm::ivec3 counts, glm::dvec3 step) {
  PatternParams p;
  p.counts = counts;
  p.step = step;
  return p;
}

PatternParams circularOf(int count, double angle, int axis = 2) {
  PatternParams p;
  p.count = count;
  p.angle = angle;
  p.axis = axis;
  return p;
}

PatternParams mirrorOf(int axis, glm::dvec3 center, bool keep) {
  PatternParams p;
  p.axis = axis;
  p.center = center;
  p.keepOriginal = keep;
  return p;
}

// An L of two boxes on the +x side: asymmetric under every mirror.
NodePtr ell() {
  return op(NodeKind::Union,
            {box({1.0, 1.0, 1.0}, {2.0, 0.0, 0.0}), box({2.0, 0.5, 1.0}, {2.5, 0.75, 0.0})});
}
constexpr double kEllVolume = 2.0;  // the boxes touch along y = 0.5

double volumeIn(const NodePtr& root, int resolution, glm::dvec3 min, glm::dvec3 max) {
  return evaluateCpu(makeSceneInBox(root, resolution, min, max)).measure.volume;
}

TEST(PatternNodes, DisjointCopiesAddTheirVolumes) {
  // Unit cubes 1.5 apart: 4 in a row, then a 2 x 3 grid.
  const double one = volumeIn(box(glm::dvec3(1.0)), 64, glm::dvec3(-2), glm::dvec3(6));
  const double row =
      volumeIn(pattern(NodeKind::Array, arrayOf({4, 1, 1}, {1.5, 0, 0}), {box(glm::dvec3(1.0))}),
               64, glm::dvec3(-2), glm::dvec3(6));
  EXPECT_NEAR(one, 1.0, 1e-9);  // faces on cell boundaries: exact
  EXPECT_NEAR(row, 4.0 * one, 0.02);
  const double grid =
      volumeIn(pattern(NodeKind::Array, arrayOf({2, 3, 1}, {1.5, 2.0, 0}), {box(glm::dvec3(1.0))}),
               64, glm::dvec3(-2), glm::dvec3(6));
  EXPECT_NEAR(grid, 6.0 * one, 0.03);
  // Six boxes on a circle of radius 3 (disjoint), and a quarter turn of 4 (0, 30, 60, 90 deg).
  const double ring = volumeIn(pattern(NodeKind::CircularArray, circularOf(6, 360.0),
                                       {box(glm::dvec3(1.0), {3.0, 0.0, 0.0})}),
                               96, glm::dvec3(-4), glm::dvec3(4));
  EXPECT_NEAR(ring, 6.0, 0.05);
  const NodePtr arc =
      pattern(NodeKind::CircularArray, circularOf(4, 90.0), {box(glm::dvec3(0.5), {3, 0, 0})});
  const Bounds b = nodeBounds(arc, arc, glm::dmat4(1.0));
  EXPECT_NEAR(b.max.y, 3.25, 1e-9);  // the last copy at 90 degrees: (0, 3)
  EXPECT_NEAR(b.min.x, -0.25, 1e-9);
  EXPECT_NEAR(b.min.y, -0.25, 1e-9);
}

TEST(PatternNodes, AMirroredPartLiesOnTheOtherSideOnly) {
  const glm::dvec3 lo(-4.0), hi(4.0);
  const NodePtr image = pattern(NodeKind::Mirror, mirrorOf(0, glm::dvec3(0.0), false), {ell()});
  // The mirrored bounding box.
  const Bounds source = nodeBounds(ell(), ell(), glm::dmat4(1.0));
  const Bounds mirrored = nodeBounds(image, image, glm::dmat4(1.0));
  EXPECT_NEAR(mirrored.min.x, -source.max.x, 1e-12);
  EXPECT_NEAR(mirrored.max.x, -source.min.x, 1e-12);
  EXPECT_EQ(mirrored.min.y, source.min.y);
  EXPECT_EQ(mirrored.max.z, source.max.z);
  // Sampled: all of it at x < 0, nothing at x > 0 (probed by intersecting half-spaces).
  const NodePtr left = box({4.0, 8.0, 8.0}, {-2.0, 0.0, 0.0});
  const NodePtr right = box({4.0, 8.0, 8.0}, {2.0, 0.0, 0.0});
  const double whole = volumeIn(image, 64, lo, hi);
  EXPECT_NEAR(whole, kEllVolume, 0.02);
  EXPECT_NEAR(volumeIn(op(NodeKind::Intersection, {image, left}), 64, lo, hi), whole, 1e-9);
  EXPECT_EQ(volumeIn(op(NodeKind::Intersection, {image, right}), 64, lo, hi), 0.0);
  // Kept with its original: twice the volume, and symmetric.
  const NodePtr both = pattern(NodeKind::Mirror, mirrorOf(0, glm::dvec3(0.0), true), {ell()});
  EXPECT_NEAR(volumeIn(both, 64, lo, hi), 2.0 * whole, 1e-6);
  // Across the plane y = 1 through a centre off the origin: the image spans 2 - y.
  const NodePtr acrossY = pattern(NodeKind::Mirror, mirrorOf(1, {0, 1, 0}, false), {ell()});
  const Bounds y = nodeBounds(acrossY, acrossY, glm::dmat4(1.0));
  EXPECT_NEAR(y.min.y, 2.0 - source.max.y, 1e-12);
  EXPECT_NEAR(y.max.y, 2.0 - source.min.y, 1e-12);
}

TEST(PatternNodes, CopiesMultiplyTheLeafCountThatGuardsTheScene) {
  const NodePtr pair = op(NodeKind::Union, {box(glm::dvec3(1.0)), sphere(0.5)});
  const NodePtr grid = pattern(NodeKind::Array, arrayOf({10, 10, 10}, glm::dvec3(2.0)), {pair});
  EXPECT_EQ(measureExpansion(grid).leaves, 2000u);
  const NodePtr nested = pattern(NodeKind::Mirror, mirrorOf(2, glm::dvec3(0.0), true), {grid});
  EXPECT_EQ(measureExpansion(nested).leaves, 4000u);
  EXPECT_THROW(checkExpansion(nested, 3999), Error);
  // At the largest counts the product saturates instead of wrapping.
  const NodePtr huge = pattern(
      NodeKind::Array, arrayOf(glm::ivec3(kMaxPatternCount), glm::dvec3(1)),
      {pattern(NodeKind::Array, arrayOf(glm::ivec3(kMaxPatternCount), glm::dvec3(1)), {pair})});
  EXPECT_GT(measureExpansion(huge).leaves, uint64_t(1) << 60);
}

// A pattern of nothing lists no copies (a hostile file of 10000^3 empty copies costs nothing),
// and counts whose product passes the cap are refused; the ghosts keep the shown copy once: a
// mirror that drops its original keeps its image, an array whose copies coincide keeps one.
TEST(PatternNodes, EmptyPatternsHugeCountsAndKeptCopies) {
  EXPECT_EQ(patternCopies(Pattern::Array, arrayOf({100, 100, 100}, glm::dvec3(1))), 1000000u);
  EXPECT_NO_THROW(checkPattern(Pattern::Array, arrayOf({1000, 1000, 1}, glm::dvec3(1)), "a"));
  EXPECT_THROW(checkPattern(Pattern::Array, arrayOf({1000, 1000, 2}, glm::dvec3(1)), "a"), Error);
  const std::string file =
      R"({"format": "strata-scene", "version": 4, "root": {"id": 1, "type": "union", "children": [)"
      R"({"id": 2, "type": "sphere"}, {"id": 3, "type": "array", "counts": [10000, 10000, 10000],)"
      R"( "step": [1, 1, 1]}]}})";
  try {
    parseScene(file, "huge.strata.json", ".");
    ADD_FAILURE() << "10000^3 copies read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/root/children/1/counts"), std::string::npos) << e.what();
  }
  // An empty array of many copies: counted as visits, listed as none, evaluated at once.
  const NodePtr empty = pattern(NodeKind::Array, arrayOf({1000, 1000, 1}, glm::dvec3(1)), {});
  EXPECT_EQ(measureExpansion(empty).nodes, 1000001u);
  const NodePtr root = op(NodeKind::Union, {sphere(1.0), empty});
  EXPECT_NEAR(evaluateCpu(makeScene(root, 32)).measure.volume, 4.18879, 0.3);

  // Kept LDIs (the editor's ghosts): the first copy, once.
  NodePtr cutter = box(glm::dvec3(0.5), {1.0, 0.0, 0.0});
  const NodePtr image = pattern(NodeKind::Mirror, mirrorOf(0, glm::dvec3(0.0), false), {cutter});
  NodePtr other = box(glm::dvec3(0.5), {3.0, 0.0, 0.0});
  const NodePtr stacked = pattern(NodeKind::Array, arrayOf({2, 5, 1}, {1.0, 0.0, 0.0}), {other});
  Scene scene = makeScene(op(NodeKind::Union, {sphere(0.2), image, stacked}), 32);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalOptions options;
  options.keep = {cutter->id, other->id};
  const EvalResult r = evaluator.evaluate(scene, options, progress);
  ASSERT_EQ(r.kept.size(), 2u);
  EXPECT_EQ(r.kept[0].id, cutter->id);
  EXPECT_EQ(r.kept[1].id, other->id);
}

TEST(PatternNodes, ACountChangedReusesTheCopiesAlreadySampled) {
  Document doc(makeScene(op(NodeKind::Union, {box(glm::dvec3(1.0))}), 48));
  const NodeId leaf = doc.root()->children[0]->id;
  const NodeId array = doc.group({leaf}, NodeKind::Array);
  doc.setPattern(array, arrayOf({3, 1, 1}, {2.0, 0, 0}));
  Scene scene = doc.scene();
  scene.settings.hasBounds = true;
  scene.settings.bounds = Bounds{glm::dvec3(-2.0), glm::dvec3(10.0)};
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  const double three = evaluator.evaluate(scene, EvalOptions{}, progress).measure.volume;
  doc.setPattern(array, arrayOf({4, 1, 1}, {2.0, 0, 0}));
  scene.root = doc.root();
  const EvalResult four = evaluator.evaluate(scene, EvalOptions{}, progress);
  EXPECT_NEAR(four.measure.volume, three * 4.0 / 3.0, 1e-6);
  int sampled = 0;
  for (const NodeRecord& r : four.nodes)
    sampled += r.kind == "box" && r.outcome == NodeOutcome::Computed ? 1 : 0;
  EXPECT_EQ(sampled, 1);  // only the new copy
  // One undo step each; refused edits change nothing.
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(findNode(doc.root(), array)->pattern.counts.x, 3);
  EXPECT_THROW(doc.setPattern(array, arrayOf({0, 1, 1}, {2.0, 0, 0})), Error);
  EXPECT_THROW(doc.setPattern(leaf, arrayOf({2, 1, 1}, {2.0, 0, 0})), Error);
  EXPECT_THROW(doc.setPattern(array, arrayOf({10000, 10000, 1}, {2.0, 0, 0})), Error);
  EXPECT_EQ(findNode(doc.root(), array)->pattern.counts.x, 3);
}

TEST(PatternNodes, SceneFilesKeepTheCopiesAndTheVersion) {
  const NodePtr root =
      op(NodeKind::Union,
         {pattern(NodeKind::Array, arrayOf({3, 2, 1}, {1.5, -2.0, 0}), {box(glm::dvec3(1.0))}),
          pattern(NodeKind::CircularArray, circularOf(5, -120.0, 0), {sphere(0.2, {0, 2, 0})}),
          pattern(NodeKind::Mirror, mirrorOf(1, {0, 0.5, 0}, false), {ell()})});
  const std::string text = sceneToJson(makeScene(root, 64));
  EXPECT_NE(text.find("\"version\": 4"), std::string::npos);
  const Scene back = parseScene(text, "patterns.strata.json", ".");
  ASSERT_EQ(back.root->children.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.root->children[i]->kind, root->children[i]->kind);
    EXPECT_EQ(back.root->children[i]->pattern, root->children[i]->pattern) << i;
  }
  EXPECT_EQ(sceneToJson(back), text);
  // Without patterns the oldest version that holds the scene.
  EXPECT_NE(sceneToJson(makeScene(ell(), 64)).find("\"version\": 1"), std::string::npos);
  // Bad values name the field.
  const std::pair<const char*, const char*> bad[] = {
      {R"("type": "array", "counts": [0, 1, 1], "step": [1, 0, 0])", "/root/counts/0"},
      {R"("type": "array", "counts": [2, 1, 1])", "/root/step"},
      {R"("type": "array", "counts": [2.5, 1, 1], "step": [1, 0, 0])", "/root/counts/0"},
      {R"("type": "circularArray", "count": 3, "angle": 0)", "/root/angle"},
      {R"("type": "circularArray", "count": 3, "angle": 400)", "/root/angle"},
      {R"("type": "circularArray", "count": 3, "axis": "w")", "/root/axis"},
      {R"("type": "mirror", "center": [0, 0, 0])", "/root/axis"},
      {R"("type": "mirror", "axis": "x", "keep": 1)", "/root/keep"},
      {R"("type": "mirror", "axis": "x", "counts": [1, 1, 1])", "/root/counts"},
  };
  for (const auto& [fields, pointer] : bad) {
    const std::string file =
        std::string(R"({"format": "strata-scene", "version": 4, "root": {"id": 1, )") + fields +
        R"(, "children": [{"id": 2, "type": "sphere"}]}})";
    try {
      parseScene(file, "bad.strata.json", ".");
      ADD_FAILURE() << "read: " << fields;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  }
  // A newer file than this build reads is refused by its version, not by its fields.
  EXPECT_THROW(parseScene(R"({"format": "strata-scene", "version": )" +
                              std::to_string(kSceneFormatVersion + 1) +
                              R"(, "root": {"id": 1, "type": "sphere"}})",
                          "new.strata.json", "."),
               Error);
}

// Files of versions 1 and 2 (the bundled demo and scaffold) read unchanged by this build: saved
// again they keep their version, and the copy evaluates to the same bits as the original.
TEST(PatternNodes, OlderScenesLoadWithTheSameResult) {
  for (const char* name : {"demo.strata.json", "bone_scaffold.strata.json"}) {
    const std::string path = assetsDir() + "/scenes/" + name;
    Scene original = loadScene(path);
    const std::string text = sceneToJson(original);
    std::ifstream in(path);
    const std::string onDisk((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
    const auto versionOf = [](const std::string& s) {
      const size_t at = s.find("\"version\":");
      return at == std::string::npos ? std::string() : s.substr(at, 13);
    };
    EXPECT_EQ(versionOf(text), versionOf(onDisk)) << name;
    Scene copy = parseScene(text, name, assetsDir() + "/scenes");
    original.settings.resolution = copy.settings.resolution = 64;
    const EvalResult a = evaluateCpu(original), b = evaluateCpu(copy);
    EXPECT_EQ(a.measure.volume, b.measure.volume) << name;
    EXPECT_EQ(a.measure.area, b.measure.area) << name;
  }
}

TEST(PatternNodes, ATiledExportIsWatertightWithOneComponentPerCopy) {
  PatternParams ring = circularOf(8, 360.0);
  const NodePtr root =
      pattern(NodeKind::Mirror, mirrorOf(2, glm::dvec3(0.0), true),
              {pattern(NodeKind::CircularArray, ring, {sphere(0.4, {1.5, 0.0, 0.8})})});
  Scene scene = makeScene(root, 64);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourOptions options;
  options.tileCells = 16;
  ContourReport report;
  ExportMesh mesh = contourScene(scene, evaluator, options, progress, &report);
  EXPECT_GT(report.tiles, 1);
  const MeshCheck check = checkMesh(mesh.mesh);
  EXPECT_TRUE(check.watertight());
  EXPECT_EQ(check.components, 16);
  EXPECT_EQ(check.genus, 0);
  EXPECT_NEAR(check.volume, 16 * 4.0 / 3.0 * 3.14159265358979 * 0.064, 0.1);
}

}  // namespace
}  // namespace strata::test

namespace strata {
namespace {

// An undo of a pattern's edit says which field it takes back ("undone: copies" whichever it was:
// an artist's test); several at once are the copies.
TEST(PatternNodes, AnUndoSaysWhichFieldOfTheCopiesItTakesBack) {
  const PatternParams a;
  PatternParams b = a;
  b.count = 6;
  EXPECT_EQ(patternChangeLabel(a, b), "copies' count");
  b.angle = 90.0;
  EXPECT_EQ(patternChangeLabel(a, b), "copies");
  PatternParams c = a;
  c.step.x = 2.0;
  EXPECT_EQ(patternChangeLabel(a, c), "copies' step");
  Document doc;
  const NodeId ring = doc.addNode(NodeKind::CircularArray);
  PatternParams p = findNode(doc.root(), ring)->pattern;
  p.angle = 180.0;
  doc.setPattern(ring, p);
  EXPECT_EQ(doc.undoLabel(), "copies' angle");
  // Each kind's words: a circular array's centre is its axis's, a mirror's its plane's.
  p.center.x = 5.0;
  doc.setPattern(ring, p);
  EXPECT_EQ(doc.undoLabel(), "axis position");
  const NodeId mirror = doc.addNode(NodeKind::Mirror);
  PatternParams m = findNode(doc.root(), mirror)->pattern;
  m.center.x = 3.0;
  doc.setPattern(mirror, m);
  EXPECT_EQ(doc.undoLabel(), "mirror plane's position");
  m.axis = 1;
  doc.setPattern(mirror, m);
  EXPECT_EQ(doc.undoLabel(), "mirror plane's direction");
}

}  // namespace
}  // namespace strata
