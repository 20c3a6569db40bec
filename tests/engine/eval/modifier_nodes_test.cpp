// Modifier nodes (offset, shell, round, fillet: engine/kinds/node_kinds.h) evaluated through the
// evaluator: volumes of analytic solids, the grid's room for a growth, caching by amount, bad
// amounts, scene files (version 2 only when needed), and a watertight export.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/document/commands.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"
#include "engine/geometry/mesh_check.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

double evaluatedVolume(const NodePtr& root, int resolution) {
  return evaluateCpu(makeScene(root, resolution)).measure.volume;
}

TEST(ModifierNodes, VolumesOfTheUnitSphereAndTwoBoxes) {
  const int res = 96;
  // Sampled at 96 cells along the (grown) bounds: about 0.03 units a cell.
  EXPECT_NEAR(evaluatedVolume(modifier(NodeKind::Offset, 0.25, {sphere(1.0)}), res), 8.18123,
              0.5 * 0.03 * 4 * kPi * 1.5625);
  EXPECT_NEAR(evaluatedVolume(modifier(NodeKind::Offset, -0.25, {sphere(1.0)}), res), 1.76715,
              0.5 * 0.025 * 4 * kPi * 0.5625);
  EXPECT_NEAR(evaluatedVolume(modifier(NodeKind::Shell, 0.1, {sphere(1.0)}), res), 1.13516,
              0.5 * 0.025 * 4 * kPi * 1.81);
  // Two unit cubes side by side touching along an edge line: a fillet fills the concave seam,
  // so it only adds; rounding removes from the convex edges, so it only takes.
  const NodePtr pair = op(
      NodeKind::Union, {box(glm::dvec3(1.0), {-0.5, 0, 0}), box(glm::dvec3(1.0), {0.5, 0.5, 0})});
  const double plain = evaluatedVolume(pair, res);
  EXPECT_NEAR(plain, 2.0, 0.05);
  EXPECT_GT(evaluatedVolume(modifier(NodeKind::Fillet, 0.2, {pair}), res), plain + 0.005);
  EXPECT_LT(evaluatedVolume(modifier(NodeKind::Round, 0.2, {pair}), res), plain - 0.05);
}

TEST(ModifierNodes, TheGridMakesRoomForAGrowth) {
  // Grown by 0.5, the sphere of radius 1 reaches 1.5: the grid must hold it whole (not cut at
  // the sphere's own bounds).
  Scene scene = makeScene(modifier(NodeKind::Offset, 0.5, {sphere(1.0)}), 64);
  const Grid grid = Evaluator::gridFor(scene, 64);
  EXPECT_LT(grid.origin.x, -1.5);
  EXPECT_NEAR(evaluateCpu(scene).measure.volume, 4.0 / 3.0 * kPi * 3.375, 0.3);
}

TEST(ModifierNodes, CachedByAmountAndBadAmountsNameTheNode) {
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  auto a = makeScene(modifier(NodeKind::Offset, 0.2, {sphere(1.0)}), 48);
  auto b = makeScene(modifier(NodeKind::Offset, 0.3, {sphere(1.0)}), 48);
  for (Scene* s : {&a, &b}) {  // one grid for both
    s->settings.hasBounds = true;
    s->settings.bounds = Bounds{glm::dvec3(-2.0), glm::dvec3(2.0)};
  }
  const double va = evaluator.evaluate(a, EvalOptions{}, progress).measure.volume;
  const double vb = evaluator.evaluate(b, EvalOptions{}, progress).measure.volume;
  EXPECT_GT(vb, va);  // a new amount is a new key, not the cached result
  EXPECT_EQ(evaluator.evaluate(a, EvalOptions{}, progress).measure.volume, va);

  auto bad = makeScene(modifier(NodeKind::Shell, 0.0, {sphere(1.0)}), 48);
  try {
    evaluator.evaluate(bad, EvalOptions{}, progress);
    ADD_FAILURE() << "a shell of thickness 0 evaluated";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("thickness must be greater than 0"), std::string::npos)
        << e.what();
  }
}

TEST(ModifierNodes, SceneFilesKeepTheAmountAndTheVersion) {
  Scene scene = makeScene(modifier(NodeKind::Round, 0.125, {box(glm::dvec3(2.0))}), 64);
  const std::string text = sceneToJson(scene);
  EXPECT_NE(text.find("\"version\": 2"), std::string::npos);
  EXPECT_NE(text.find("\"radius\": 0.125"), std::string::npos) << text;
  Scene back = parseScene(text, "round.strata.json", ".");
  EXPECT_EQ(back.root->kind, NodeKind::Round);
  EXPECT_EQ(back.root->amount, 0.125);
  // Without modifiers the file stays version 1 (older builds read it).
  EXPECT_NE(sceneToJson(makeScene(sphere(1.0), 64)).find("\"version\": 1"), std::string::npos);
  // A modifier without its amount, or a bad one, is refused with the field's path.
  for (const char* bad : {R"("type": "shell")", R"("type": "shell", "thickness": -1)",
                          R"("type": "offset", "distance": "1")"}) {
    const std::string file =
        std::string(R"({"format": "strata-scene", "version": 2, "root": {"id": 1, )") + bad +
        R"(, "children": [{"id": 2, "type": "sphere"}]}})";
    EXPECT_THROW(parseScene(file, "bad.strata.json", "."), Error) << bad;
  }
}

TEST(ModifierNodes, ExportsPassTheWatertightCheck) {
  Scene scene = makeScene(
      modifier(NodeKind::Fillet, 0.15,
               {op(NodeKind::Union, {sphere(0.6, {-0.5, 0, 0}), sphere(0.6, {0.5, 0, 0})})}),
      64);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourOptions options;
  options.tileCells = 16;  // asked for tiles: a modifier's scene is exported in one
  ContourReport report;
  ExportMesh mesh = contourScene(scene, evaluator, options, progress, &report);
  EXPECT_EQ(report.tiles, 1);
  const MeshCheck check = checkMesh(mesh.mesh);
  EXPECT_TRUE(check.watertight());
  EXPECT_EQ(check.components, 1);
  EXPECT_GT(check.volume, 2 * 4.0 / 3.0 * kPi * 0.216 * 0.9);
}

}  // namespace
}  // namespace strata::test
