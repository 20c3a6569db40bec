// Numbers out of range are errors or warnings, never a silent zero: scales that underflow,
// parts too far out for their size, and parts smaller than a cell.
#include <gtest/gtest.h>

#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

std::string evaluationError(const Scene& scene) {
  try {
    test::evaluateCpu(scene);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LeafPlacement, NestedScalesThatUnderflowNameTheLeaf) {
  auto cube = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  cube->name = "tiny cube";
  NodePtr node = cube;
  NodeId id = 3;
  for (int i = 0; i < 40; ++i) {
    auto wrap = std::make_shared<Node>(*makeOperationNode(NodeKind::Union, id++, {node}));
    wrap->transform.scale = glm::dvec3(1e-10);
    node = wrap;
  }
  Scene scene = test::makeSceneInBox(makeOperationNode(NodeKind::Union, 1, {node}), 16,
                                     glm::dvec3(-1.0), glm::dvec3(1.0));
  const std::string m = evaluationError(scene);
  EXPECT_NE(m.find("box 'tiny cube'"), std::string::npos) << m;
  EXPECT_NE(m.find("underflows"), std::string::npos) << m;
}

// A scene whose volume and area doubles cannot measure (a box of 1e308 measured an infinite
// volume, one of 1e-300 a volume of 0, both "successfully"; a box 1e300 from the origin): refused
// before any work, with its size.
TEST(LeafPlacement, ScenesTooLargeOrTooSmallToMeasureAreRefused) {
  EXPECT_NE(evaluationError(test::makeScene(test::box(glm::dvec3(1e308)), 16)).find("1e+308 units"),
            std::string::npos);
  EXPECT_NE(
      evaluationError(test::makeScene(test::box(glm::dvec3(1e-300)), 16)).find("1e-300 units"),
      std::string::npos);
  EXPECT_NE(evaluationError(test::makeScene(test::box(glm::dvec3(1.0), glm::dvec3(1e300)), 16))
                .find("from the origin"),
            std::string::npos);
  // Bounds given by the scene itself are held to the same.
  EXPECT_NE(evaluationError(test::makeSceneInBox(test::box(glm::dvec3(1.0)), 16, glm::dvec3(-1e308),
                                                 glm::dvec3(1e308)))
                .find("units"),
            std::string::npos);
  EXPECT_EQ(evaluationError(test::makeScene(test::box(glm::dvec3(1e90)), 16)), "");
  EXPECT_EQ(evaluationError(test::makeScene(test::box(glm::dvec3(1e-90)), 16)), "");
}

TEST(LeafPlacement, APartTooFarOutForItsSizeIsRefused) {
  auto cube = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  cube->name = "far cube";
  cube->transform.translate.x = 1e308;
  Scene scene = test::makeSceneInBox(makeOperationNode(NodeKind::Union, 1, {cube}), 16,
                                     glm::dvec3(-1.0), glm::dvec3(1.0));
  const std::string m = evaluationError(scene);
  EXPECT_NE(m.find("box 'far cube'"), std::string::npos) << m;
  EXPECT_NE(m.find("cannot be represented"), std::string::npos) << m;
}

TEST(LeafPlacement, APartSmallerThanACellIsNamedInTheWarnings) {
  auto big = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  auto speck = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Sphere, 3));
  speck->name = "speck";
  speck->params.radius = 1e-4;
  speck->transform.translate.x = 0.3;
  EvalResult r =
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, speck}), 32));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("sphere 'speck'"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("smaller than a cell"), std::string::npos) << r.warnings[0];
  // Lengths in the scene's unit (an artist read "(20; a cell is 15.6)" without one).
  EXPECT_NE(r.warnings[0].find("mm across) is smaller than a cell ("), std::string::npos)
      << r.warnings[0];
  // Cached on the next evaluation, still said.
  EvalResult again =
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, speck}), 32));
  EXPECT_EQ(again.warnings.size(), 1u);
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

TEST(LeafPlacement, APartThinnerThanTwoCellsIsNamedWithTheResolutionItNeeds) {
  auto big = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  auto sheet = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 3));
  sheet->name = "sheet";
  sheet->params.size = glm::dvec3(0.8, 0.8, 0.02);  // a cell is about 1/32 of the box
  EvalResult r =
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, sheet}), 32));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("box 'sheet' is only"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("cells thick"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("(0.02 mm; a cell is "), std::string::npos) << r.warnings[0];
  // At a resolution that makes it thick enough, nothing is said.
  EXPECT_TRUE(
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, sheet}), 256))
          .warnings.empty());
}

// A thin sheet turned about an axis in its plane (so that its world box is as deep as it is wide)
// is still as thin as it is: said by the evaluation and before it (an artist's 0.3 mm shim turned
// 113 degrees was exported in 36 strips without a word), and by its thickness, not its box's.
TEST(LeafPlacement, ATurnedThinSheetIsStillSaidToBeThin) {
  auto big = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  auto sheet = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 3));
  sheet->name = "shim";
  sheet->params.size = glm::dvec3(0.8, 0.8, 0.02);
  sheet->transform.rotateDegrees = glm::dvec3(0.0, 113.0, 0.0);
  const Scene scene = test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, sheet}), 32);
  const EvalResult r = test::evaluateCpu(scene);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("box 'shim' is only"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("(0.02 mm; a cell is "), std::string::npos) << r.warnings[0];
  EXPECT_EQ(Evaluator::smallPartWarnings(scene, 32), r.warnings);
  // Turned and scaled unevenly inside a turned group (a sheared box): still its true thickness.
  auto group = std::make_shared<Node>(*makeOperationNode(NodeKind::Union, 4, {sheet}));
  group->transform.scale = glm::dvec3(1.0, 1.0, 3.0);
  group->transform.rotateDegrees = glm::dvec3(30.0, 0.0, 0.0);
  const Scene sheared = test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, group}), 32);
  const std::vector<std::string> said = Evaluator::smallPartWarnings(sheared, 32);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_NE(said[0].find("box 'shim' is only"), std::string::npos) << said[0];
  // A cube turned the same way is as thick as it is: nothing said.
  auto cube = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 5));
  cube->params.size = glm::dvec3(0.5);
  cube->transform.rotateDegrees = glm::dvec3(0.0, 113.0, 45.0);
  EXPECT_TRUE(
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, cube}), 32))
          .warnings.empty());
}

// One part far from the rest stretches the grid: said first (it is why the others come out
// smaller than a cell), with by how much; two parts far apart, which a scene means to hold, and a
// cutter reaching beyond its part are not said.
TEST(LeafPlacement, APartFarFromTheRestIsSaidFirst) {
  auto plate = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  auto boss = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 3));
  boss->params.size = glm::dvec3(0.3);
  boss->transform.translate = glm::dvec3(0.2, 0.0, 0.6);
  auto stray = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 4));
  stray->name = "stray";
  stray->params.size = glm::dvec3(0.2);
  stray->transform.translate = glm::dvec3(100.0, 0.0, 0.0);
  const Scene scene =
      test::makeScene(makeOperationNode(NodeKind::Union, 1, {plate, boss, stray}), 32);
  const EvalResult r = test::evaluateCpu(scene);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("box 'stray' lies far from the rest"), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("as large"), std::string::npos) << r.warnings[0];
  EXPECT_GT(r.warnings.size(), 1u) << "the plate and the boss are now smaller than a cell";
  EXPECT_EQ(Evaluator::smallPartWarnings(scene, 32), r.warnings);

  // Two parts far apart: neither alone stretches the grid.
  auto twin = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 5));
  twin->transform.translate = glm::dvec3(100.0, 0.0, 0.0);
  for (const std::string& w : Evaluator::smallPartWarnings(
           test::makeScene(makeOperationNode(NodeKind::Union, 1, {plate, twin}), 32), 32))
    EXPECT_EQ(w.find("lies far"), std::string::npos) << w;
  // A cutter far beyond its part (and the part near the rest): nothing stretches.
  auto bore = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Cylinder, 6));
  bore->params.height = 200.0;
  auto cut = std::make_shared<Node>(*makeOperationNode(NodeKind::Difference, 7, {plate, bore}));
  const EvalResult clean =
      test::evaluateCpu(test::makeScene(makeOperationNode(NodeKind::Union, 1, {cut, boss}), 32));
  for (const std::string& w : clean.warnings) EXPECT_EQ(w.find("lies far"), std::string::npos) << w;
}

// Before an export at its own resolution runs, the same sentences from the parts' bounds alone
// (the export dialog says them): each once however many copies a pattern makes.
TEST(LeafPlacement, SmallPartsAreNamedBeforeAnythingIsEvaluated) {
  auto big = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  auto sheet = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 3));
  sheet->name = "sheet";
  sheet->params.size = glm::dvec3(0.8, 0.8, 0.02);
  auto copies = std::make_shared<Node>(*makeOperationNode(NodeKind::Array, 4, {sheet}));
  copies->pattern.counts = glm::ivec3(1, 1, 5);
  copies->pattern.step = glm::dvec3(0.0, 0.0, 0.1);
  const Scene scene = test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, copies}), 32);
  const std::vector<std::string> before = Evaluator::smallPartWarnings(scene, 32);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_EQ(before[0], test::evaluateCpu(scene).warnings.at(0)) << "what the evaluation says";
  EXPECT_TRUE(Evaluator::smallPartWarnings(scene, 256).empty());
  // A mesh node kept without its file (meshMissing) is said too: it will not be in the file.
  auto lost = std::make_shared<Node>(
      *makeMeshNode(5, "scan", std::make_shared<TriangleMesh>(), "/nowhere/scan.stl", ""));
  const Scene withLost =
      test::makeScene(makeOperationNode(NodeKind::Union, 1, {big, copies, lost}), 256);
  const std::vector<std::string> said = Evaluator::smallPartWarnings(withLost, 256);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_NE(said[0].find("'scan' has no mesh"), std::string::npos) << said[0];
  EXPECT_EQ(said[0], test::evaluateCpu(withLost).warnings.at(0));
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// An open mesh that is one flat sheet was refused with "lies 0 from the origin along z, where its
// size of 0 cannot be represented in double precision", which stopped the whole scene; one flat
// but for rounding (turned +Y up: 6e-16 thick) was "only 1.8e-15 cells thick; about 2.2e+15x the
// resolution makes it 4 cells thick". Both are evaluated and said to be flat, the rest of the
// scene with them. A part whose thickness is lost to its distance from the origin still gets
// the precision error.
TEST(LeafPlacement, AFlatSheetIsSaidToBeFlat) {
  auto sheet = std::make_shared<TriangleMesh>();
  sheet->positions = {{0, 0, 0.25}, {1, 0, 0.25}, {1, 1, 0.25}, {0, 1, 0.25}};
  sheet->triangles = {{0, 1, 2}, {0, 2, 3}};
  for (const double turn : {0.0, 90.0}) {
    auto node =
        std::make_shared<Node>(*makeMeshNode(2, "sheet", sheet, "/tmp/sheet.obj", "", true));
    node->transform.rotateDegrees.x = turn;  // a quarter turn leaves rounding for thickness
    auto cube = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 3));
    Scene scene = test::makeSceneInBox(makeOperationNode(NodeKind::Union, 1, {node, cube}), 16,
                                       glm::dvec3(-1.0), glm::dvec3(2.0));
    const EvalResult r = test::evaluateCpu(scene);
    ASSERT_EQ(r.warnings.size(), 1u) << turn;
    EXPECT_NE(r.warnings[0].find("'sheet' is flat (no thickness)"), std::string::npos)
        << r.warnings[0];
    const EvalResult alone = test::evaluateCpu(test::makeSceneInBox(
        makeOperationNode(NodeKind::Union, 1, {cube}), 16, glm::dvec3(-1.0), glm::dvec3(2.0)));
    EXPECT_DOUBLE_EQ(r.measure.volume, alone.measure.volume) << "the sheet adds nothing";
  }
  auto far = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  far->name = "far cube";
  far->transform.translate.z = 1e300;
  const std::string f = evaluationError(test::makeSceneInBox(
      makeOperationNode(NodeKind::Union, 1, {far}), 16, glm::dvec3(-1.0), glm::dvec3(1.0)));
  EXPECT_NE(f.find("cannot be represented"), std::string::npos) << f;
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// A modifier that left nothing says by how much, in the scene's unit.
TEST(LeafPlacement, AnEmptiedModifierSaysItsAmountsInTheScenesUnit) {
  auto box = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, 2));
  box->params.size = glm::dvec3(1.0, 1.0, 1.0);
  auto shrunk = std::make_shared<Node>(*makeOperationNode(NodeKind::Offset, 3, {box}));
  shrunk->amount = -0.75;
  auto other = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Sphere, 4));
  other->transform.translate.x = 3.0;
  const EvalResult r = test::evaluateCpu(
      test::makeScene(makeOperationNode(NodeKind::Union, 1, {shrunk, other}), 32));
  bool said = false;
  for (const std::string& w : r.warnings)
    said = said || w.find("shrinking by 0.75 mm removes every part thinner than 1.5 mm") !=
                       std::string::npos;
  EXPECT_TRUE(said) << (r.warnings.empty() ? std::string("no warnings") : r.warnings[0]);
}

}  // namespace
}  // namespace strata
