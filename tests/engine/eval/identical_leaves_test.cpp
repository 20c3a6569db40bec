// Identical leaves share one sampled LDI, and the Booleans drop repeated operands: a union of
// thousands of copies of a box costs one sampling and no Boolean, and gives the box.
#include <gtest/gtest.h>

#include "engine/document/commands.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

NodePtr boxAt(NodeId id, double x) {
  auto b = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Box, id));
  b->transform.translate.x = x;
  return b;
}

TEST(IdenticalLeaves, ThousandsOfCopiesCostOneSampling) {
  std::vector<NodePtr> copies;
  for (NodeId id = 2; id < 5002; ++id) copies.push_back(boxAt(id, 0.0));
  Scene many = test::makeScene(makeOperationNode(NodeKind::Union, 1, copies), 64);
  EvalResult r = test::evaluateCpu(many);
  EXPECT_EQ(r.computed, 1);  // one sampling; the union passes it through
  Scene one = test::makeScene(makeOperationNode(NodeKind::Union, 1, {boxAt(2, 0.0)}), 64);
  EvalResult single = test::evaluateCpu(one);
  EXPECT_EQ(r.measure.volume, single.measure.volume);
  EXPECT_EQ(r.measure.surfels, single.measure.surfels);
}

TEST(IdenticalLeaves, ADifferenceWithItsBaseAmongTheCuttersIsEmpty) {
  NodePtr diff =
      makeOperationNode(NodeKind::Difference, 1, {boxAt(2, 0.0), boxAt(3, 0.3), boxAt(4, 0.0)});
  EvalResult r = test::evaluateCpu(test::makeSceneInBox(diff, 32, glm::dvec3(-1), glm::dvec3(1)));
  EXPECT_EQ(r.measure.surfels, 0u);
  EXPECT_EQ(r.measure.volume, 0.0);
}

TEST(IdenticalLeaves, RepeatedCuttersCutOnce) {
  auto cutTwice = makeOperationNode(
      NodeKind::Difference, 1, {boxAt(2, 0.0), boxAt(3, 0.375), boxAt(4, 0.375), boxAt(5, 0.375)});
  auto cutOnce = makeOperationNode(NodeKind::Difference, 1, {boxAt(2, 0.0), boxAt(3, 0.375)});
  const glm::dvec3 lo(-1.0), hi(1.5);
  EvalResult a = test::evaluateCpu(test::makeSceneInBox(cutTwice, 40, lo, hi));
  EvalResult b = test::evaluateCpu(test::makeSceneInBox(cutOnce, 40, lo, hi));
  EXPECT_EQ(a.measure.volume, b.measure.volume);
  EXPECT_NEAR(a.measure.volume, 0.375, 1e-9);
}

TEST(IdenticalLeaves, DifferentPlacesAreNotShared) {
  NodePtr u = makeOperationNode(NodeKind::Union, 1, {boxAt(2, 0.0), boxAt(3, 2.0)});
  EvalResult r = test::evaluateCpu(test::makeScene(u, 64));
  EXPECT_EQ(r.computed, 3);                 // two samplings and the union
  EXPECT_NEAR(r.measure.volume, 2.0, 0.3);  // off-grid faces: within area * h / 2
}

}  // namespace
}  // namespace strata
