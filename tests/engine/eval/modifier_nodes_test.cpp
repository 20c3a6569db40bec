// Modifier nodes (offset, shell, round, fillet: engine/kinds/node_kinds.h) evaluated through the
// evaluator: volumes of analytic solids, the grid's room for a growth, caching by amount, bad
// amounts, scene files (version 2 only when needed, 3 for a shell's opening), a shell opened
// where a chosen part cuts it, and a watertight export.
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

// A modifier that leaves nothing of its parts says so, naming the node and why; cached, it still
// does; one that keeps something says nothing.
TEST(ModifierNodes, AModifierThatLeavesNothingSaysWhy) {
  const NodePtr plate = box({4.0, 4.0, 0.4});
  auto round = std::make_shared<Node>(*modifier(NodeKind::Round, 0.3, {plate}));
  round->name = "edges";
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalOptions options;
  options.resolution = 64;
  const Scene emptied = makeScene(round, 64);
  for (int pass = 0; pass < 2; ++pass) {  // computed, then from the cache
    const EvalResult r = evaluator.evaluate(emptied, options, progress);
    EXPECT_EQ(r.measure.surfels, 0u);
    ASSERT_EQ(r.warnings.size(), 1u) << "pass " << pass;
    EXPECT_NE(r.warnings[0].find("round 'edges' left nothing"), std::string::npos) << r.warnings[0];
    EXPECT_NE(r.warnings[0].find("thinner than 0.6"), std::string::npos) << r.warnings[0];
  }
  const EvalResult kept =
      evaluator.evaluate(makeScene(modifier(NodeKind::Round, 0.1, {plate}), 64), options, progress);
  EXPECT_GT(kept.measure.surfels, 0u);
  EXPECT_TRUE(kept.warnings.empty());
  // In an export's tiles: a tile that holds only the thin plate of a shrunk block-and-plate has
  // nothing left of it, but the block is kept elsewhere: no warning (one was said per tile).
  const Scene tiled = makeScene(
      modifier(NodeKind::Offset, -0.1,
               {box({1.0, 1.0, 1.0}, {-1.0, 0.0, 0.0}), box({2.0, 1.0, 0.1}, {1.0, 0.0, 0.0})}),
      64);
  ContourReport report;
  const ExportMesh mesh = contourScene(tiled, evaluator, ContourOptions{64, 16}, progress, &report);
  EXPECT_GT(report.tiles, 4);
  EXPECT_GT(mesh.mesh.triangles.size(), 100u);
  for (const std::string& w : report.warnings)
    EXPECT_EQ(w.find("left nothing"), std::string::npos) << w;
}

// A coarse preview passes modifiers under its cells through: the result is the children's own
// (the same surfels as the unmodified part, from the same cache entry), and each is named; a
// modifier of several cells, and every modifier when none are skipped, applies.
TEST(ModifierNodes, ModifiersUnderTheSkippedCellsPassThrough) {
  const NodePtr plate = box({4.0, 4.0, 0.6});
  auto round = std::make_shared<Node>(*modifier(NodeKind::Round, 0.1, {plate}));
  round->name = "rim";
  auto grow = std::make_shared<Node>(*modifier(NodeKind::Offset, 0.5, {round}));
  grow->name = "pad";
  const Scene scene = makeScene(grow, 32);  // h = 0.2: the round is half a cell, the pad 2.5
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalOptions skip;
  skip.resolution = 32;
  skip.skipModifiersUnderCells = 2.0;
  const EvalResult coarse = evaluator.evaluate(scene, skip, progress);
  ASSERT_EQ(coarse.skippedModifiers.size(), 1u);
  EXPECT_EQ(coarse.skippedModifiers[0], "round 'rim'");
  const Grid grid = coarse.grid;
  EXPECT_LT(0.1, 2.0 * grid.h);
  EXPECT_GT(0.5, 2.0 * grid.h);
  // The pad of the unrounded plate, on the same grid.
  const EvalResult plain =
      evaluator.evaluateOn(makeScene(modifier(NodeKind::Offset, 0.5, {plate}), 32), grid, progress);
  EXPECT_EQ(coarse.measure.volume, plain.measure.volume);
  EXPECT_EQ(coarse.measure.surfels, plain.measure.surfels);
  EvalOptions all = skip;
  all.skipModifiersUnderCells = 0.0;
  const EvalResult full = evaluator.evaluate(scene, all, progress);
  EXPECT_TRUE(full.skippedModifiers.empty());
  EXPECT_LT(full.measure.volume, coarse.measure.volume - 0.01);  // the round took the edges
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

// The unit sphere with its top cut off by a box (z > 0.5), shelled by 0.1 (scene builder ids).
NodePtr cappedSphereShell(NodeId* cutter) {
  NodePtr top = box(glm::dvec3(4.0, 4.0, 1.0), glm::dvec3(0.0, 0.0, 1.0));
  *cutter = top->id;
  return modifier(NodeKind::Shell, 0.1, {op(NodeKind::Difference, {sphere(1.0), top})});
}

// The number of surfels on the z ray nearest the z axis.
size_t surfelsOnTheAxis(const Ldi& ldi) {
  const Grid& g = ldi.grid;
  const AxisLdi& a = ldi.axes[2];
  const int64_t raysU = g.cells.x + 1;
  int64_t bestRay = 0;
  double bestDistance = 1e300;
  for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray) {
    const double x = g.origin.x + g.h * double(g.first.x + ray % raysU);
    const double y = g.origin.y + g.h * double(g.first.y + ray / raysU);
    if (std::abs(x) + std::abs(y) < bestDistance) {
      bestDistance = std::abs(x) + std::abs(y);
      bestRay = ray;
    }
  }
  return a.offsets[size_t(bestRay) + 1] - a.offsets[size_t(bestRay)];
}

// A shell whose opening is the cutter: the wall follows the sphere, not the cut, so the cavity
// reaches out through the cut. Along the axis: the closed shell has a bottom wall and a top
// wall under the cut (four surfels), the opened one only the bottom wall (two). Volumes: the
// sphere below z = 0.5 minus the sphere of 0.9 below z = 0.5 (0.866033) against the closed
// shell's 1.056622.
TEST(ModifierNodes, AShellOpensWhereItsOpeningCuts) {
  constexpr double kOpened = 0.866033, kClosed = 1.056622;
  for (int resolution : {48, 96}) {
    NodeId cutter = 0;
    NodePtr closed = cappedSphereShell(&cutter);
    auto opened = std::make_shared<Node>(*closed);
    opened->opening = cutter;
    EXPECT_EQ(shellOpening(opened)->id, cutter);
    const EvalResult a = evaluateCpu(makeScene(closed, resolution));
    const EvalResult b = evaluateCpu(makeScene(opened, resolution));
    const auto closedLdi = CpuBackend().download(a.root);
    const auto openedLdi = CpuBackend().download(b.root);
    const double h = closedLdi->grid.h;
    EXPECT_EQ(surfelsOnTheAxis(*closedLdi), 4u) << resolution;
    EXPECT_EQ(surfelsOnTheAxis(*openedLdi), 2u) << resolution;
    // Half a cell times the area: the outer and inner spherical zones, and the ring at the cut
    // (opened) or the two disks of the top wall (closed).
    EXPECT_NEAR(b.measure.volume, kOpened, 0.5 * h * (3.0 * kPi + 2.8 * kPi * 0.9 + 0.6));
    EXPECT_NEAR(a.measure.volume, kClosed, 0.5 * h * (3.0 * kPi + 2.6 * kPi * 0.9 + 4.4));
    EXPECT_GT(a.measure.volume - b.measure.volume, 0.1);  // the top wall, about 0.19
  }
  // An opening that names no part inside the shell leaves the wall closed.
  NodeId cutter = 0;
  auto dangling = std::make_shared<Node>(*cappedSphereShell(&cutter));
  dangling->opening = 999999;
  EXPECT_EQ(shellOpening(dangling), nullptr);
  EXPECT_EQ(withoutOpening(dangling), nullptr);
}

TEST(ModifierNodes, AShellsOpeningIsSavedAsVersion3AndFollowsCopies) {
  NodeId cutter = 0;
  auto shell = std::make_shared<Node>(*cappedSphereShell(&cutter));
  shell->opening = cutter;
  const std::string text = sceneToJson(makeScene(shell, 64));
  EXPECT_NE(text.find("\"version\": 3"), std::string::npos);
  EXPECT_NE(text.find("\"opening\": " + std::to_string(cutter)), std::string::npos) << text;
  Scene back = parseScene(text, "opened.strata.json", ".");
  EXPECT_EQ(back.root->opening, cutter);
  // A copy's opening names the copy of the part, not the original.
  auto root = op(NodeKind::Union, {shell});
  NodeId copyId = 0;
  NodePtr after = duplicateNode(root, shell->id, maxNodeId(root) + 1, &copyId);
  NodePtr copy = findNode(after, copyId);
  ASSERT_TRUE(copy);
  ASSERT_TRUE(shellOpening(copy));
  EXPECT_NE(copy->opening, cutter);
  EXPECT_EQ(findNode(copy, copy->opening)->kind, NodeKind::Box);
  // An opening outside the shell (or the shell itself) is refused, naming the field.
  for (const char* opening : {"1", "7"}) {
    const std::string file =
        std::string(R"({"format": "strata-scene", "version": 3, "root": {"id": 1, "type": )") +
        R"("shell", "thickness": 0.1, "opening": )" + opening +
        R"(, "children": [{"id": 2, "type": "sphere"}]}})";
    try {
      parseScene(file, "bad.strata.json", ".");
      ADD_FAILURE() << "accepted opening " << opening;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("/root/opening"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("not inside this shell"), std::string::npos) << e.what();
    }
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
  options.tileCells = 16;  // in tiles, each evaluated with the fillet's reach around it
  ContourReport report;
  ExportMesh mesh = contourScene(scene, evaluator, options, progress, &report);
  EXPECT_GT(report.tiles, 8);
  const MeshCheck check = checkMesh(mesh.mesh);
  EXPECT_TRUE(check.watertight());
  EXPECT_EQ(check.components, 1);
  EXPECT_GT(check.volume, 2 * 4.0 / 3.0 * kPi * 0.216 * 0.9);
}

// A flat face on a grid plane: an offset's surfel through a node sat at the node's own depth,
// which gave that node the new state on its ray alone; the contour met the rays' disagreement
// with a crossing at the edge's middle, and the face of a filleted or rounded L came out half a
// cell out (a numbers check: at 128 and 192 cells, not at 96 or 256). Every face on a plane of
// nodes here; the faces must stay where they are, with no disagreement.
TEST(ModifierNodes, AFaceOnAGridPlaneStaysWhereItIs) {
  const NodePtr shape = op(NodeKind::Union, {box({2.0, 1.0, 1.0}, {1.0, 0.5, 0.5}),
                                             box({1.0, 2.0, 1.0}, {0.5, 1.0, 0.5})});
  for (NodeKind kind : {NodeKind::Fillet, NodeKind::Round}) {
    // h = 1/32: the L's faces (0, 1 and 2) and the fillet's reach all lie on planes of nodes.
    Scene scene =
        makeSceneInBox(modifier(kind, 0.3, {shape}), 96, {-0.5, -0.5, -0.5}, {2.5, 2.5, 2.5});
    Evaluator evaluator(std::make_shared<CpuBackend>());
    Progress progress;
    ContourReport report;
    ExportMesh mesh = contourScene(scene, evaluator, ContourOptions{}, progress, &report);
    const double h = report.grid.h;
    ASSERT_NEAR(h, 1.0 / 32.0, 1e-12);
    EXPECT_EQ(report.signDisagreements, 0u) << kindName(kind);
    EXPECT_EQ(report.synthesizedCrossings, 0u) << kindName(kind);
    double worst = 0.0;  // beyond the faces y = 1 (for x > 1.4) and x = 1 (for y > 1.4)
    for (const glm::dvec3& p : mesh.mesh.positions) {
      if (p.x > 1.4 && p.x < 1.9) worst = std::max(worst, p.y - 1.0);
      if (p.y > 1.4 && p.y < 1.9) worst = std::max(worst, p.x - 1.0);
    }
    EXPECT_LT(worst, 0.02 * h) << kindName(kind) << ": a face moved by " << worst / h << " h";
  }
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

// A CPU backend that notes the evaluation's progress when an offset starts and ends.
class OffsetWatchingBackend : public CpuBackend {
 public:
  explicit OffsetWatchingBackend(const double* progress) : progress_(progress) {}
  LdiHandle offset(const LdiHandle& ldi, double distance, Progress& progress) override {
    before = *progress_;
    LdiHandle out = CpuBackend::offset(ldi, distance, progress);
    after = *progress_;
    return out;
  }
  double before = -1.0, after = -1.0;

 private:
  const double* progress_;
};

// An offset's passes over every lattice node took two thirds of the bone scaffold's evaluation at
// 768 cells while the bar sat at 33% (one unit of progress, as a leaf's sampling): an artist's
// test. A modifier's visit now moves the bar by about its share of the work, the bar never goes
// back, and it ends at 1.
TEST(ModifierNodes, AnOffsetMovesTheProgressBarByItsShareOfTheWork) {
  double last = 0.0;
  bool backwards = false;
  Progress progress([&](const std::string& stage, double f) {
    if (stage != "evaluate") return;
    backwards = backwards || f < last - 1e-12;
    last = f;
  });
  auto backend = std::make_shared<OffsetWatchingBackend>(&last);
  Evaluator evaluator(backend);
  const Scene scene = makeScene(
      op(NodeKind::Union,
         {modifier(NodeKind::Offset, 0.1, {sphere(1.0)}), box(glm::dvec3(0.5), {1.5, 0, 0}),
          box(glm::dvec3(0.5), {-1.5, 0, 0}), box(glm::dvec3(0.5), {0, 1.5, 0})}),
      48);
  evaluator.evaluate(scene, EvalOptions{}, progress);
  ASSERT_GE(backend->before, 0.0) << "the offset ran";
  EXPECT_GT(backend->after - backend->before, 0.5)
      << "the offset's share of the bar: " << backend->before << " to " << backend->after;
  EXPECT_FALSE(backwards);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

}  // namespace
}  // namespace strata::test
