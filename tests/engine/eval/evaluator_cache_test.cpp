// The evaluator's content-keyed cache: after one leaf changes, only its path to the root is
// recomputed, and the result equals a fresh evaluation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

// union(difference(box, cylinder), sphere, intersection(sphere, box))
struct Tree {
  NodePtr block = box({2, 2, 1});
  NodePtr drill = cylinder(0.3, 2.0);
  NodePtr ball = sphere(0.6, {1.2, 0, 0});
  NodePtr lensA = sphere(0.5, {-1.2, 0, 0.2});
  NodePtr lensB = box({0.6, 0.6, 0.6}, {-1.2, 0, 0});
  NodePtr cut = op(NodeKind::Difference, {block, drill});
  NodePtr lens = op(NodeKind::Intersection, {lensA, lensB});
  NodePtr root = op(NodeKind::Union, {cut, ball, lens});
};

Scene fixedGrid(NodePtr root) {
  return makeSceneInBox(std::move(root), 96, {-2.5, -2.5, -2.5}, {2.5, 2.5, 2.5});
}

int computedOf(const EvalResult& r, NodeId id) {
  for (const auto& n : r.nodes)
    if (n.id == id) return n.outcome == NodeOutcome::Computed ? 1 : 0;
  return -1;
}

TEST(EvaluatorCache, SecondEvaluationReusesEverything) {
  Tree t;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalResult first = evaluator.evaluate(fixedGrid(t.root), {}, progress);
  EXPECT_EQ(first.computed, 8);
  EXPECT_EQ(first.reused, 0);
  EvalResult second = evaluator.evaluate(fixedGrid(t.root), {}, progress);
  EXPECT_EQ(second.computed, 0);
  EXPECT_EQ(second.reused, 8);
  EXPECT_EQ(second.root, first.root);  // the very same LDI
}

TEST(EvaluatorCache, MovingOneLeafRecomputesOnlyItsPath) {
  Tree t;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  evaluator.evaluate(fixedGrid(t.root), {}, progress);

  // Move the drill: a new drill, a new difference, a new root; everything else is shared.
  Transform moved = t.drill->transform;
  moved.translate.x += 0.25;
  NodePtr drill = withTransform(t.drill, moved);
  auto cut = std::make_shared<Node>(*t.cut);
  cut->children = {t.block, drill};
  auto root = std::make_shared<Node>(*t.root);
  root->children = {cut, t.ball, t.lens};
  EvalResult edited = evaluator.evaluate(fixedGrid(root), {}, progress);
  EXPECT_EQ(edited.computed, 3);  // drill, cut, root
  EXPECT_EQ(computedOf(edited, t.drill->id), 1);
  EXPECT_EQ(computedOf(edited, t.block->id), 0);
  EXPECT_EQ(computedOf(edited, t.lens->id), 0);
  EXPECT_EQ(computedOf(edited, t.ball->id), 0);

  // Same answer as evaluating from scratch.
  EvalResult fresh = evaluateCpu(fixedGrid(root));
  EXPECT_EQ(edited.measure.volume, fresh.measure.volume);
  EXPECT_EQ(edited.measure.surfels, fresh.measure.surfels);
}

// A CPU backend that records how the evaluator asks for leaves: the size of every
// sampleMeshes call and how many single sampleMesh calls there were.
class CountingBackend : public CpuBackend {
 public:
  std::vector<LdiHandle> sampleMeshes(const std::vector<LeafToSample>& leaves, const Grid& grid,
                                      Progress& progress) override {
    batches.push_back(leaves.size());
    return CpuBackend::sampleMeshes(leaves, grid, progress);
  }
  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    ++singles;
    return CpuBackend::sampleMesh(mesh, objectToWorld, grid, leafId, progress);
  }
  std::vector<size_t> batches;
  int singles = 0;
};

TEST(EvaluatorCache, LeavesAreSampledInOneBatch) {
  Tree t;
  auto backend = std::make_shared<CountingBackend>();
  Evaluator evaluator(backend);
  Progress progress;
  EvalResult first = evaluator.evaluate(fixedGrid(t.root), {}, progress);
  ASSERT_EQ(backend->batches, std::vector<size_t>{5});  // every leaf, in one call
  EXPECT_EQ(backend->singles, 5);                       // the default: one by one
  EXPECT_EQ(computedOf(first, t.drill->id), 1);
  EXPECT_EQ(first.stages[1].name, "sample");
  EXPECT_EQ(first.stages[1].runs, 5);

  // Nothing new: no call at all. One leaf moved: a batch of one.
  evaluator.evaluate(fixedGrid(t.root), {}, progress);
  EXPECT_EQ(backend->batches.size(), 1u);
  Transform moved = t.ball->transform;
  moved.translate.y += 0.3;
  auto root = std::make_shared<Node>(*t.root);
  root->children = {t.cut, withTransform(t.ball, moved), t.lens};
  evaluator.evaluate(fixedGrid(root), {}, progress);
  EXPECT_EQ(backend->batches, (std::vector<size_t>{5, 1}));

  // Identical leaves (same content, same place) are sampled once; the result equals a fresh
  // evaluation's on a backend that samples one leaf at a time.
  NodePtr copies = op(NodeKind::Union, {box({1, 1, 1}), box({1, 1, 1}), sphere(0.7, {0.5, 0, 0})});
  auto counting = std::make_shared<CountingBackend>();
  Evaluator batched(counting);
  EvalResult b = batched.evaluate(fixedGrid(copies), {}, progress);
  EXPECT_EQ(counting->batches, std::vector<size_t>{2});
  EvalResult fresh = evaluateCpu(fixedGrid(copies));
  EXPECT_EQ(b.measure.volume, fresh.measure.volume);
  EXPECT_EQ(b.computed, fresh.computed);
}

// Big leaves go in groups of at least a million triangles (about an eighth of all), and the
// evaluation's progress moves after each group, never backwards, to the end.
TEST(EvaluatorCache, BigLeavesAreSampledInGroupsWithProgress) {
  std::vector<NodePtr> spheres;
  for (int k = 0; k < 8; ++k) {
    auto s = std::make_shared<Node>(*sphere(0.4, {-2.0 + 0.55 * k, 0.0, 0.0}));
    s->params.segments = 512;  // about 260,000 triangles each
    spheres.push_back(s);
  }
  auto root = std::make_shared<Node>(*op(NodeKind::Union, {}));
  root->children = spheres;
  auto backend = std::make_shared<CountingBackend>();
  Evaluator evaluator(backend);
  std::vector<double> fractions;
  Progress progress([&](const std::string& stage, double fraction) {
    if (stage == "evaluate") fractions.push_back(fraction);
  });
  EvalResult r =
      evaluator.evaluate(makeSceneInBox(root, 48, {-3, -3, -3}, {3, 3, 3}), {}, progress);
  ASSERT_GE(backend->batches.size(), 2u);
  size_t sampled = 0;
  for (size_t b : backend->batches) sampled += b;
  EXPECT_EQ(sampled, 8u);
  EXPECT_EQ(r.computed, 9);
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_DOUBLE_EQ(fractions.back(), 1.0);
  EXPECT_LT(fractions.front(), 0.5);  // the first group's share, before any Boolean
}

TEST(EvaluatorCache, ResolutionChangeRecomputesAndHiddenNodesAreSkipped) {
  Tree t;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  EvalResult a = evaluator.evaluate(fixedGrid(t.root), {}, progress);
  EvalOptions finer;
  finer.resolution = 128;
  EvalResult b = evaluator.evaluate(fixedGrid(t.root), finer, progress);
  EXPECT_EQ(b.computed, 8);
  EXPECT_NEAR(a.measure.volume, b.measure.volume, 0.05 * a.measure.volume);

  auto hiddenBall = std::make_shared<Node>(*t.ball);
  hiddenBall->visible = false;
  auto root = std::make_shared<Node>(*t.root);
  root->children = {t.cut, hiddenBall, t.lens};
  EvalResult hidden = evaluator.evaluate(fixedGrid(root), {}, progress);
  EXPECT_EQ(computedOf(hidden, t.ball->id), -1);  // not visited at all
  EXPECT_LT(hidden.measure.volume, a.measure.volume);
}

// A hidden root hides the whole scene, as a hidden child hides its part (a numbers check found
// a scene whose root was hidden exported whole): refused as empty, with or without bounds.
TEST(EvaluatorCache, AHiddenRootHidesTheWholeScene) {
  Tree t;
  auto root = std::make_shared<Node>(*t.root);
  root->visible = false;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  for (const Scene& scene : {fixedGrid(root), makeScene(root, 64)}) {
    try {
      evaluator.evaluate(scene, {}, progress);
      ADD_FAILURE() << "a hidden root was evaluated";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("root"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("hidden"), std::string::npos) << e.what();
    }
    EXPECT_THROW(evaluator.evaluateOn(scene, Evaluator::gridFor(fixedGrid(t.root), 64), progress),
                 Error);
  }
}

// Bounds of the scene's own smaller than its parts cut them flat: said (a numbers check found
// it silent), naming the side and how far they reach; bounds around them say nothing.
TEST(EvaluatorCache, BoundsThatCutThePartsAreSaid) {
  const NodePtr ball = sphere(1.0);
  const auto warned = [](const EvalResult& r) {
    for (const std::string& w : r.warnings)
      if (w.find("settings.bounds") != std::string::npos) return w;
    return std::string();
  };
  const EvalResult cut = evaluateCpu(makeSceneInBox(ball, 64, glm::dvec3(-1.2), {1.2, 1.2, 0.5}));
  const std::string said = warned(cut);
  EXPECT_NE(said.find("z up to 1 (the bounds end at 0.5)"), std::string::npos) << said;
  EXPECT_EQ(said.find("x "), std::string::npos) << said;
  EXPECT_TRUE(
      warned(evaluateCpu(makeSceneInBox(ball, 64, glm::dvec3(-1.2), glm::dvec3(1.2)))).empty());
  // A turned sphere is still the sphere (its local box turned reached 1.41).
  Transform turned;
  turned.rotateDegrees = glm::dvec3(45.0, 30.0, 0.0);
  EXPECT_TRUE(warned(evaluateCpu(makeSceneInBox(withTransform(ball, turned), 64, glm::dvec3(-1.05),
                                                glm::dvec3(1.05))))
                  .empty());
}

TEST(EvaluatorCache, InstancesShowTheirTargetEvenWhenItIsHidden) {
  NodePtr part = sphere(0.5);
  auto hidden = std::make_shared<Node>(*part);
  hidden->visible = false;
  auto copyA = std::make_shared<Node>();
  copyA->id = 90001;
  copyA->kind = NodeKind::Instance;
  copyA->instanceOf = hidden->id;
  copyA->transform.translate = {-1, 0, 0};
  auto copyB = std::make_shared<Node>(*copyA);
  copyB->id = 90002;
  copyB->transform.translate = {1, 0, 0};
  NodePtr root = op(NodeKind::Union, {hidden, copyA, copyB});
  EvalResult r = evaluateCpu(fixedGrid(root));
  EvalResult one = evaluateCpu(fixedGrid(sphere(0.5)));
  // Two copies (not three: the hidden template itself is not drawn), up to sampling noise.
  EXPECT_NEAR(r.measure.volume, 2 * one.measure.volume, 0.02 * one.measure.volume);
}

// Chains of one Boolean are evaluated as one (Evaluator: flattened): a chain of 8 unions of
// cells that are instances of a union of struts, intersected with a chain of intersections,
// minus a chain of differences whose cutters are unions: 3 Booleans instead of 27, and the root
// is, surfel for surfel, what the nested evaluation gives (every operation kept for its own LDI
// is never merged: the same tree evaluated level by level).
TEST(EvaluatorCache, ChainsOfOneBooleanAreOneBooleanWithTheSameSurfels) {
  std::vector<NodeId> operations;
  auto keepOp = [&](NodePtr n) {
    operations.push_back(n->id);
    return n;
  };
  NodePtr strut = keepOp(op(NodeKind::Union, {cylinder(0.08, 0.9), sphere(0.15, {0, 0, 0.3})}));
  auto hidden = std::make_shared<Node>(*strut);
  hidden->visible = false;
  NodePtr chain = keepOp(op(NodeKind::Union, {sphere(0.2, {-1.2, 0, 0}), hidden}));
  for (int i = 0; i < 8; ++i) {
    auto cell = std::make_shared<Node>();
    cell->id = 95000 + NodeId(i);
    cell->kind = NodeKind::Instance;
    cell->instanceOf = hidden->id;
    cell->transform.translate = {-1.0 + 0.3 * i, 0.1 * (i % 3), 0};
    chain = keepOp(op(NodeKind::Union, {chain, cell}));
  }
  NodePtr lens = keepOp(
      op(NodeKind::Intersection,
         {keepOp(op(NodeKind::Intersection, {box({3, 1, 1}), sphere(1.45)})), box({2.6, 2, 2})}));
  NodePtr both = keepOp(op(NodeKind::Intersection, {chain, lens}));
  NodePtr drilled = keepOp(op(
      NodeKind::Difference,
      {keepOp(op(NodeKind::Difference, {both, cylinder(0.1, 2.0, {0.5, 0, 0})})),
       keepOp(op(NodeKind::Union, {box({0.2, 0.2, 2.0}, {-0.5, 0, 0}),
                                   keepOp(op(NodeKind::Union, {sphere(0.2, {0.2, 0.3, 0})}))}))}));
  const Scene scene = fixedGrid(drilled);
  Progress progress;
  Evaluator flat(std::make_shared<CpuBackend>()), nested(std::make_shared<CpuBackend>());
  const EvalResult a = flat.evaluate(scene, {}, progress);
  EvalOptions keepAll;
  keepAll.keep = operations;
  const EvalResult b = nested.evaluate(scene, keepAll, progress);
  auto booleans = [](const EvalResult& r) {
    for (const auto& st : r.stages)
      if (st.name == "boolean") return st.runs;
    return -1;
  };
  EXPECT_EQ(booleans(a), 3);  // the union of cells, the intersection, the difference
  EXPECT_GE(booleans(b), 14);
  int merged = 0;
  for (const auto& n : a.nodes) merged += n.outcome == NodeOutcome::Merged ? 1 : 0;
  EXPECT_GE(merged, 12);
  const auto x = wholeLdi(flat.backend().download(a.root));
  const auto y = wholeLdi(nested.backend().download(b.root));
  size_t surfels = 0;
  for (int axis = 0; axis < 3; ++axis) {
    ASSERT_EQ(x->axes[axis].offsets, y->axes[axis].offsets) << "axis " << axis;
    ASSERT_EQ(x->axes[axis].surfels.size(), y->axes[axis].surfels.size());
    surfels += x->axes[axis].surfels.size();
    EXPECT_EQ(0, std::memcmp(x->axes[axis].surfels.data(), y->axes[axis].surfels.data(),
                             x->axes[axis].surfels.size() * sizeof(Surfel)))
        << "axis " << axis;
  }
  EXPECT_GT(surfels, 1000u);
  EXPECT_EQ(a.measure.volume, b.measure.volume);
}

// The editor's preview grid follows the scene on one lattice (Evaluator::previewGridFor): a part
// moved out past the scene's bounds grows the window, and the parts left alone (a round, a
// fillet, a difference with its cutter, an offset) are reused from the cache, moved onto the new
// window; the result equals, surfel for surfel, a fresh evaluation on that grid.
TEST(EvaluatorCache, APartMovedOutKeepsTheOthersCachedOnTheGrownWindow) {
  auto plate = std::make_shared<Node>(*modifier(NodeKind::Round, 0.15, {box({2, 2, 0.6})}));
  auto seam = std::make_shared<Node>(
      *modifier(NodeKind::Fillet, 0.1,
                {box({0.6, 0.6, 0.6}, {0, 1.4, 0}), box({0.6, 0.6, 0.6}, {0.6, 1.9, 0})}));
  auto pad =
      std::make_shared<Node>(*modifier(NodeKind::Offset, 0.1, {sphere(0.3, {-1.3, -1.3, 0})}));
  const NodePtr drilled = op(NodeKind::Difference, {plate, cylinder(0.3, 2.0, {0.4, -0.4, 0})});
  auto ball = std::make_shared<Node>(*sphere(0.4, {1.6, 0, 0}));  // moved in place below
  Scene scene = makeScene(op(NodeKind::Union, {drilled, seam, pad, ball}), 96);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  const Grid before = Evaluator::previewGridFor(scene, 96, nullptr);
  const EvalResult first = evaluator.evaluateOn(scene, before, progress);
  const int nodes = first.computed;

  Grid previous = before;
  for (const double x : {2.0, 1.0, -2.4}) {  // out along +x, back in, out along -x
    ball->transform.translate = {x, 0, 0};
    const Grid grid = Evaluator::previewGridFor(scene, 96, &previous);
    EXPECT_FALSE(grid == previous) << "x " << x;
    previous = grid;
    EXPECT_EQ(grid.origin, before.origin);
    EXPECT_EQ(grid.h, before.h);
    const EvalResult moved = evaluator.evaluateOn(scene, grid, progress);
    EXPECT_EQ(moved.grid, grid);
    std::string computed;
    for (const auto& n : moved.nodes)
      if (n.outcome == NodeOutcome::Computed) computed += n.kind + " ";
    // The ball, the root, and the drill, whose ends stick out of both windows (clipped, it
    // cannot be moved); the difference it cuts lies within them: reused.
    EXPECT_EQ(computed, "cylinder sphere union ") << "x " << x << " (of " << nodes << ")";
    Evaluator fresh(std::make_shared<CpuBackend>());
    const EvalResult again = fresh.evaluateOn(scene, grid, progress);
    const auto a = wholeLdi(evaluator.backend().download(moved.root));
    const auto b = wholeLdi(fresh.backend().download(again.root));
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_EQ(a->axes[axis].offsets, b->axes[axis].offsets) << "x " << x << " axis " << axis;
      ASSERT_EQ(a->axes[axis].surfels.size(), b->axes[axis].surfels.size());
      EXPECT_EQ(0, std::memcmp(a->axes[axis].surfels.data(), b->axes[axis].surfels.data(),
                               a->axes[axis].surfels.size() * sizeof(Surfel)))
          << "x " << x << " axis " << axis;
    }
  }
}

// A fresh lattice where the cells would drift too far from the resolution asked for, or the
// window would leave its room; the same one while the scene stays within.
TEST(EvaluatorCache, ThePreviewGridFollowsItsLatticeWithinItsSlack) {
  auto ball = std::make_shared<Node>(*sphere(0.5));  // moved in place below
  Scene scene = makeScene(op(NodeKind::Union, {box({2, 2, 2}), ball}), 128);
  const Grid first = Evaluator::previewGridFor(scene, 128, nullptr);
  const Grid plain = Evaluator::gridFor(scene, 128);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(first.bounds().min[a], plain.bounds().min[a], 1e-12);
  EXPECT_EQ(first.cells, plain.cells);
  EXPECT_EQ(first.first, glm::ivec3(32));
  ball->transform.translate = {0.3, 0, 0};  // inside the box's bounds still: the same grid
  EXPECT_EQ(Evaluator::previewGridFor(scene, 128, &first), first);
  ball->transform.translate = {0.7, 0, 0};  // 0.2 beyond: the window grows on the lattice
  const Grid grown = Evaluator::previewGridFor(scene, 128, &first);
  EXPECT_EQ(grown.origin, first.origin);
  EXPECT_GT(grown.cells.x, first.cells.x);
  ball->transform.translate = {4.0, 0, 0};  // the scene twice as long: a new lattice
  const Grid relaid = Evaluator::previewGridFor(scene, 128, &grown);
  EXPECT_NE(relaid.h, first.h);
  EXPECT_EQ(std::max({relaid.cells.x, relaid.cells.y, relaid.cells.z}), 128);
  // Explicit bounds keep their exact grid.
  Scene boxed = makeSceneInBox(sphere(1.0), 64, {-2, -2, -2}, {2, 2, 2});
  EXPECT_EQ(Evaluator::previewGridFor(boxed, 64, &first), Evaluator::gridFor(boxed, 64));
}

// evaluateCached computes nothing: nothing where a node is missing (the cache as it was), the
// evaluation itself where every node is held, with the root's key of a full evaluation.
TEST(EvaluatorCache, AnEvaluationFromTheCacheAloneComputesNothing) {
  Tree t;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  const Scene scene = fixedGrid(t.root);
  const Grid grid = Evaluator::gridFor(scene, 0);
  EXPECT_FALSE(evaluator.evaluateCached(scene, grid, progress));
  EXPECT_EQ(evaluator.cacheEntries(), 0u);
  const EvalResult full = evaluator.evaluateOn(scene, grid, progress);
  const size_t entries = evaluator.cacheEntries();
  const std::optional<EvalResult> again = evaluator.evaluateCached(scene, grid, progress);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->computed, 0);
  EXPECT_EQ(again->rootKey, full.rootKey);
  EXPECT_EQ(again->measure.volume, full.measure.volume);
  auto moved = std::make_shared<Node>(*t.ball);
  moved->transform.translate = {1.1, 0, 0};
  const Scene edited = fixedGrid(op(NodeKind::Union, {t.cut, moved, t.lens}));
  EXPECT_FALSE(evaluator.evaluateCached(edited, grid, progress));
  EXPECT_EQ(evaluator.cacheEntries(), entries);  // nothing computed, nothing dropped
  const EvalResult after = evaluator.evaluateOn(edited, grid, progress);
  EXPECT_NE(after.rootKey, full.rootKey);
  EXPECT_EQ(evaluator.evaluateCached(scene, grid, progress)->rootKey, full.rootKey);  // undo
}

TEST(EvaluatorCache, CancelStopsTheEvaluation) {
  Tree t;
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  progress.cancel();
  EXPECT_THROW(evaluator.evaluate(fixedGrid(t.root), {}, progress), Cancelled);

  // Cancelling from another thread while a large evaluation runs.
  Progress running([](const std::string&, double) {});
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    running.cancel();
  });
  EvalOptions big;
  big.resolution = 2048;
  EXPECT_THROW(evaluator.evaluate(fixedGrid(t.root), big, running), Cancelled);
  canceller.join();
}

}  // namespace
}  // namespace strata::test
