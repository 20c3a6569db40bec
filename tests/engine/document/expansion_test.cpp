// Expansion through instances is counted before anything walks it: a tiny tree that doubles
// forty times is measured at once and refused with its count, naming how to raise the limit.
#include <gtest/gtest.h>

#include "engine/document/commands.h"
#include "engine/document/expansion.h"
#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

NodePtr instanceOf(NodeId id, NodeId target, double dx) {
  auto n = std::make_shared<Node>();
  n->id = id;
  n->kind = NodeKind::Instance;
  n->name = "copy " + std::to_string(id);
  n->instanceOf = target;
  n->transform.translate.x = dx;
  return n;
}

// A box, then `levels` unions each holding two instances of the one below: 2^levels leaves.
NodePtr doublingTree(int levels) {
  std::vector<NodePtr> top;
  top.push_back(makePrimitiveNode(NodeKind::Box, 2));
  NodeId below = 2, next = 3;
  for (int l = 0; l < levels; ++l) {
    NodeId u = next++;
    NodePtr a = instanceOf(next++, below, 0.0), b = instanceOf(next++, below, 0.5);
    auto level = std::make_shared<Node>(*makeOperationNode(NodeKind::Union, u, {a, b}));
    level->visible = l + 1 == levels;  // only the last level shows; the others are templates
    top.push_back(level);
    below = u;
  }
  auto& first = const_cast<Node&>(*top.front());
  first.visible = false;
  return makeOperationNode(NodeKind::Union, 1, top);
}

TEST(Expansion, CountsAnExponentialTreeWithoutWalkingIt) {
  TreeExpansion e = measureExpansion(doublingTree(40));
  EXPECT_EQ(e.leaves, uint64_t(1) << 40);
  EXPECT_EQ(e.depth, 42);  // root, 40 unions, the box
  EXPECT_FALSE(e.cycle);
  EXPECT_FALSE(e.missingTarget);
  try {
    checkExpansion(doublingTree(40), kDefaultMaxLeaves);
    ADD_FAILURE() << "a tree of 2^40 leaves was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("1,099,511,627,776 visible leaves"), std::string::npos) << m;
    EXPECT_NE(m.find("--max-leaves"), std::string::npos) << m;
    EXPECT_NE(m.find("maxLeaves"), std::string::npos) << m;
  }
}

TEST(Expansion, SaturatesInsteadOfOverflowing) {
  // 2^70 leaves: deeper than files allow, but a document can hold it.
  TreeExpansion e = measureExpansion(doublingTree(70));
  EXPECT_EQ(e.leaves, kSaturated);
  EXPECT_EQ(countText(e.leaves), "more than 10^19");
}

TEST(Expansion, HiddenNodesCountOnlyThroughInstances) {
  NodePtr hidden = makePrimitiveNode(NodeKind::Sphere, 2);
  auto h = std::make_shared<Node>(*hidden);
  h->visible = false;
  NodePtr root = makeOperationNode(NodeKind::Union, 1,
                                   {h, makePrimitiveNode(NodeKind::Box, 3), instanceOf(4, 2, 1.0)});
  TreeExpansion e = measureExpansion(root);
  EXPECT_EQ(e.leaves, 2u);  // the box and the instance of the hidden sphere
  EXPECT_EQ(e.nodes, 3u);   // the root and those two
}

TEST(Expansion, FindsCyclesAndMissingTargets) {
  NodePtr loop = makeOperationNode(NodeKind::Union, 1, {instanceOf(2, 1, 0.0)});
  EXPECT_TRUE(measureExpansion(loop).cycle);
  EXPECT_THROW(checkExpansion(loop, kDefaultMaxLeaves), Error);
  NodePtr dangling = makeOperationNode(NodeKind::Union, 1, {instanceOf(2, 99, 0.0)});
  EXPECT_TRUE(measureExpansion(dangling).missingTarget);
}

TEST(Expansion, TheEvaluatorRefusesBeforeWorkAndTheLimitCanBeRaised) {
  Scene scene = test::makeScene(doublingTree(40), 32);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EXPECT_THROW(evaluator.evaluate(scene, {}, progress), Error);
  Scene small = test::makeScene(doublingTree(4), 32);  // 16 leaves
  small.settings.maxLeaves = 8;
  EXPECT_THROW(evaluator.evaluate(small, {}, progress), Error);
  small.settings.maxLeaves = 16;
  EXPECT_GT(evaluator.evaluate(small, {}, progress).measure.volume, 0.0);
}

}  // namespace
// A shell with an opening evaluates its children twice (as they are, and without the opening for
// its wall): the count, which bounds the work and the progress, says so.
TEST(Expansion, AShellWithAnOpeningCountsItsChildrenTwice) {
  NodePtr body = test::sphere(1.0), hole = test::box(glm::dvec3(0.5));
  auto shell = std::make_shared<Node>(
      *test::modifier(NodeKind::Shell, 0.1, {test::op(NodeKind::Difference, {body, hole})}));
  EXPECT_EQ(measureExpansion(shell).leaves, 2u);
  EXPECT_EQ(measureExpansion(shell).nodes, 4u);
  shell->opening = hole->id;
  EXPECT_EQ(measureExpansion(shell).leaves, 4u);
  EXPECT_EQ(measureExpansion(shell).nodes, 8u);
}

// Modifier visits are counted apart (the evaluator's progress weighs them): through patterns'
// copies and instances, a shell with an opening's children twice, hidden ones not at all.
TEST(Expansion, ModifierVisitsAreCountedThroughCopiesAndInstances) {
  NodePtr grown = test::modifier(NodeKind::Offset, 0.1, {test::sphere(1.0)});
  auto array = std::make_shared<Node>(*test::op(NodeKind::Array, {grown}));
  array->pattern.counts = glm::ivec3(3, 1, 1);
  array->pattern.step = glm::dvec3(3.0, 0.0, 0.0);
  EXPECT_EQ(measureExpansion(array).modifiers, 3u);
  auto hidden =
      std::make_shared<Node>(*test::modifier(NodeKind::Round, 0.1, {test::box(glm::dvec3(1.0))}));
  hidden->visible = false;
  auto root = std::make_shared<Node>(*test::op(NodeKind::Union, {array, hidden}));
  EXPECT_EQ(measureExpansion(root).modifiers, 3u);
  auto inner = test::modifier(NodeKind::Offset, 0.05, {test::sphere(1.0)});
  NodePtr hole = test::box(glm::dvec3(0.5));
  auto shell = std::make_shared<Node>(
      *test::modifier(NodeKind::Shell, 0.1, {test::op(NodeKind::Difference, {inner, hole})}));
  EXPECT_EQ(measureExpansion(shell).modifiers, 2u);
  shell->opening = hole->id;
  EXPECT_EQ(measureExpansion(shell).modifiers, 3u);
}

}  // namespace strata
