// Grid-aligned solids whose faces, edges and corners lie exactly on rays: the watertight tie
// rule and the coincident-event handling must give exact answers here.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/eval/cpu_backend.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

// Grid over [-1, 3]^3 with h = 1/16: integer coordinates are grid nodes.
Scene alignedScene(NodePtr root, int resolution = 64) {
  return makeSceneInBox(std::move(root), resolution, {-1, -1, -1}, {3, 3, 3});
}

std::shared_ptr<const Ldi> hostRoot(const EvalResult& r) {
  CpuBackend cpu;
  return cpu.download(r.root);
}

TEST(CoincidentFaces, UnitCubeOnGridNodesHasExactVolume) {
  EvalResult r = evaluateCpu(alignedScene(box({1, 1, 1}, {0.5, 0.5, 0.5})));
  EXPECT_DOUBLE_EQ(r.measure.volume, 1.0);
  for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(r.measure.axisVolume[a], 1.0);
  // 16 x 16 rays per axis cross the cube, each with exactly one enter and one exit.
  EXPECT_EQ(r.measure.surfels, size_t(3 * 16 * 16 * 2));
}

TEST(CoincidentFaces, CubesSharingAFaceUniteWithoutSeam) {
  for (int resolution : {32, 64}) {
    NodePtr a = box({1, 1, 1}, {0.5, 0.5, 0.5});
    NodePtr b = box({1, 1, 1}, {1.5, 0.5, 0.5});
    EvalResult r = evaluateCpu(alignedScene(op(NodeKind::Union, {a, b}), resolution));
    EXPECT_DOUBLE_EQ(r.measure.volume, 2.0) << resolution;
    // No surfel may remain on the shared face x = 1 (grid depth (1 - -1) / h).
    auto ldi = hostRoot(r);
    const float shared = float((1.0 - r.grid.origin.x) / r.grid.h);
    for (const Surfel& s : ldi->axes[0].surfels) EXPECT_NE(s.depth, shared);
    // Every x ray through the pair has exactly one interval.
    for (size_t ray = 0; ray + 1 < ldi->axes[0].offsets.size(); ++ray) {
      uint32_t n = ldi->axes[0].offsets[ray + 1] - ldi->axes[0].offsets[ray];
      EXPECT_TRUE(n == 0 || n == 2) << "ray " << ray << " has " << n << " surfels";
    }
  }
}

TEST(CoincidentFaces, CubesSharingAnEdgeAndACorner) {
  NodePtr a = box({1, 1, 1}, {0.5, 0.5, 0.5});
  NodePtr edge = box({1, 1, 1}, {1.5, 1.5, 0.5});
  NodePtr corner = box({1, 1, 1}, {1.5, 1.5, 1.5});
  EvalResult r = evaluateCpu(alignedScene(op(NodeKind::Union, {a, edge, corner})));
  EXPECT_DOUBLE_EQ(r.measure.volume, 3.0);
}

TEST(CoincidentFaces, SolidMinusItselfIsEmpty) {
  for (NodePtr a : {box({1, 1, 1}, {0.5, 0.5, 0.5}), sphere(0.8, {1, 1, 1}),
                    cylinder(0.5, 1.5, {1, 1, 1}, {30, 40, 0})}) {
    EvalResult r = evaluateCpu(alignedScene(op(NodeKind::Difference, {a, a})));
    EXPECT_EQ(r.measure.surfels, 0u) << a->name;
    EXPECT_EQ(r.measure.volume, 0.0);
  }
}

TEST(CoincidentFaces, SolidUnionItselfIsItself) {
  for (NodePtr a : {box({1, 1, 1}, {0.5, 0.5, 0.5}), sphere(0.8, {1, 1, 1})}) {
    EvalResult alone = evaluateCpu(alignedScene(a));
    EvalResult twice = evaluateCpu(alignedScene(op(NodeKind::Union, {a, a})));
    EvalResult meet = evaluateCpu(alignedScene(op(NodeKind::Intersection, {a, a})));
    auto x = hostRoot(alone), y = hostRoot(twice), z = hostRoot(meet);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(x->axes[axis].offsets, y->axes[axis].offsets);
      EXPECT_EQ(x->axes[axis].offsets, z->axes[axis].offsets);
      ASSERT_EQ(x->axes[axis].surfels.size(), y->axes[axis].surfels.size());
      for (size_t k = 0; k < x->axes[axis].surfels.size(); ++k)
        EXPECT_EQ(x->axes[axis].surfels[k].depth, y->axes[axis].surfels[k].depth);
    }
    EXPECT_DOUBLE_EQ(alone.measure.volume, twice.measure.volume);
  }
}

TEST(CoincidentFaces, TouchingDifferenceLeavesNoSliver) {
  // [0,2]x[0,1]^2 minus [1,2]x[0,1]^2 (faces coincide on three sides) = the unit cube exactly.
  NodePtr slab = box({2, 1, 1}, {1, 0.5, 0.5});
  NodePtr cut = box({1, 1, 1}, {1.5, 0.5, 0.5});
  EvalResult r = evaluateCpu(alignedScene(op(NodeKind::Difference, {slab, cut})));
  EXPECT_DOUBLE_EQ(r.measure.volume, 1.0);
  EXPECT_EQ(r.measure.surfels, size_t(3 * 16 * 16 * 2));
}

TEST(CoincidentFaces, MirroredLeafKeepsOutwardNormals) {
  Transform mirror;
  mirror.translate = {1, 1, 1};
  mirror.scale = {-1, 1, 1};
  NodePtr a = withTransform(box({1, 1, 1}), mirror);
  EvalResult r = evaluateCpu(alignedScene(a));
  EXPECT_DOUBLE_EQ(r.measure.volume, 1.0);
  auto ldi = hostRoot(r);
  for (int axis = 0; axis < 3; ++axis)
    for (const Surfel& s : ldi->axes[axis].surfels) {
      float n[3];
      decodeNormal(s.normal, n);
      // Entering surfels face against the ray, exiting ones along it.
      EXPECT_EQ(surfelEnters(s.tag), n[axis] < 0) << axis;
    }
}

}  // namespace
}  // namespace strata::test
