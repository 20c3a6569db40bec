// Windowed axes (AxisLdi::whole == false): a small solid on a big grid stores offsets only for
// the rays it can reach, and every Boolean over windowed children equals, bit for bit, the same
// Boolean over the same children made whole. Windows are a storage choice and must never change
// a result.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

#include "engine/kinds/primitives.h"
#include "engine/ldi/combine_ldi.h"
#include "engine/ldi/sample_mesh.h"
#include "engine/ldi/splats.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

void expectSameLdi(const Ldi& x, const Ldi& y, const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    ASSERT_TRUE(x.axes[a].whole && y.axes[a].whole) << what;
    ASSERT_EQ(x.axes[a].offsets, y.axes[a].offsets) << what << " axis " << a;
    ASSERT_EQ(x.axes[a].surfels.size(), y.axes[a].surfels.size()) << what << " axis " << a;
    for (size_t k = 0; k < x.axes[a].surfels.size(); ++k) {
      const Surfel& s = x.axes[a].surfels[k];
      const Surfel& t = y.axes[a].surfels[k];
      ASSERT_TRUE(s.depth == t.depth && s.normal == t.normal && s.tag == t.tag)
          << what << " axis " << a << " surfel " << k;
    }
  }
}

std::shared_ptr<const Ldi> sampleBox(const Grid& grid, glm::dvec3 at, glm::dvec3 size,
                                     uint32_t leaf) {
  PrimitiveParams p;
  p.size = size;
  const TriangleMesh box = tessellatePrimitive(NodeKind::Box, p, 0);
  return sampleMesh(box, glm::translate(glm::dmat4(1.0), at), grid, leaf);
}

TEST(WindowedLdi, SmallSolidStoresOnlyItsRays) {
  Bounds b;
  b.min = glm::dvec3(-50.0);
  b.max = glm::dvec3(50.0);
  const Grid grid = makeGrid(b, 512, 0.0);
  auto small = sampleBox(grid, glm::dvec3(3.0, -7.0, 11.0), glm::dvec3(1.0), 1);
  for (int a = 0; a < 3; ++a) {
    EXPECT_FALSE(small->axes[a].whole);
    EXPECT_LT(small->axes[a].window.rayCount(), 100);
  }
  EXPECT_LT(small->bytes(), 16u * 1024u);  // a whole axis alone would be 1 MiB of offsets
  // The same surfels, seen whole, as splats.
  auto whole = wholeLdi(small);
  EXPECT_EQ(buildSplats(*small).size(), buildSplats(*whole).size());
  EXPECT_EQ(measureLdi(*small).volume, measureLdi(*whole).volume);
  EXPECT_NEAR(measureLdi(*small).volume, 1.0, 0.1);
  // A solid over most of the grid is stored whole.
  auto big = sampleBox(grid, glm::dvec3(0.0), glm::dvec3(90.0), 2);
  for (int a = 0; a < 3; ++a) EXPECT_TRUE(big->axes[a].whole);
}

TEST(WindowedLdi, BooleansMatchWholeChildrenBitForBit) {
  Bounds b;
  b.min = glm::dvec3(-10.0);
  b.max = glm::dvec3(10.0);
  const Grid grid = makeGrid(b, 64, 0.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(-9.0, 6.0), size(0.3, 4.0);
  std::vector<std::shared_ptr<const Ldi>> pieces;
  uint32_t leaf = 1;
  for (int k = 0; k < 24; ++k)
    pieces.push_back(
        sampleBox(grid, glm::dvec3(at(rng), at(rng), at(rng)),
                  glm::dvec3(size(rng), size(rng), size(rng)) * (k % 6 == 0 ? 4.0 : 1.0), leaf++));
  // Coincident faces: two boxes sharing a face, and one box twice.
  pieces.push_back(sampleBox(grid, glm::dvec3(0.0), glm::dvec3(2.0), leaf++));
  pieces.push_back(sampleBox(grid, glm::dvec3(2.0, 0.0, 0.0), glm::dvec3(2.0), leaf++));
  pieces.push_back(pieces.back());
  auto bunny = test::dataMesh("bunny.obj");
  const Bounds bb = meshBounds(*bunny);
  const double scale = 8.0 / std::max({bb.size().x, bb.size().y, bb.size().z});
  pieces.push_back(sampleMesh(*bunny,
                              glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) *
                                  glm::translate(glm::dmat4(1.0), -bb.center()),
                              grid, leaf++));
  std::vector<std::shared_ptr<const Ldi>> wholePieces;
  for (const auto& p : pieces) wholePieces.push_back(wholeLdi(p));

  std::uniform_int_distribution<size_t> pick(0, pieces.size() - 1);
  for (int trial = 0; trial < 60; ++trial) {
    const RayOp op = RayOp(trial % 3);
    const size_t n = 1 + size_t(trial % 7);
    std::vector<std::shared_ptr<const Ldi>> windowed, whole, mixed;
    for (size_t k = 0; k < n; ++k) {
      const size_t p = pick(rng);
      windowed.push_back(pieces[p]);
      whole.push_back(wholePieces[p]);
      mixed.push_back(k % 2 ? pieces[p] : wholePieces[p]);
    }
    const std::string what = "trial " + std::to_string(trial);
    auto reference = wholeLdi(combineLdis(op, whole, grid));
    expectSameLdi(*wholeLdi(combineLdis(op, windowed, grid)), *reference, what);
    expectSameLdi(*wholeLdi(combineLdis(op, mixed, grid)), *reference, what + " mixed");
    // A windowed result as the child of another Boolean.
    auto inner = combineLdis(op, windowed, grid);
    const RayOp outer = RayOp((trial + 1) % 3);
    const size_t other = pick(rng);
    expectSameLdi(*wholeLdi(combineLdis(outer, {inner, pieces[other]}, grid)),
                  *wholeLdi(combineLdis(outer, {wholeLdi(inner), wholePieces[other]}, grid)),
                  what + " nested");
  }
}

TEST(WindowedLdi, ManyChildrenOnOneRaySortLikeFew) {
  // 200 nested boxes: every ray through the middle crosses 400 surfels of 200 children, sorted
  // by std::stable_sort rather than by insertion; the union is the biggest box.
  Bounds b;
  b.min = glm::dvec3(-10.0);
  b.max = glm::dvec3(10.0);
  const Grid grid = makeGrid(b, 32, 0.0);
  std::vector<std::shared_ptr<const Ldi>> boxes;
  for (int k = 0; k < 200; ++k)
    boxes.push_back(sampleBox(grid, glm::dvec3(0.0), glm::dvec3(2.0 + 0.07 * k), uint32_t(k + 1)));
  auto all = combineLdis(RayOp::Union, boxes, grid);
  expectSameLdi(*wholeLdi(all), *wholeLdi(combineLdis(RayOp::Union, {boxes.back()}, grid)),
                "nested union");
  EXPECT_EQ(combineLdis(RayOp::Intersection, boxes, grid)->surfelCount(),
            combineLdis(RayOp::Union, {boxes.front()}, grid)->surfelCount());
}

// An LDI moved onto another window of its lattice (rewindowLdi) is, ray for ray, what sampling
// on that window gives, for a small (windowed) and a large (whole) solid, onto a larger window
// shifted against it and back onto a smaller one; rays the solid does not reach stay empty.
TEST(WindowedLdi, RewindowedLdisEqualSamplingOnTheNewWindow) {
  Bounds b;
  b.min = glm::dvec3(-10.0);
  b.max = glm::dvec3(10.0);
  const Grid lattice = makeGrid(b, 64, 0.0);
  const Grid a = lattice.window({10, 12, 14}, {40, 38, 36});
  const Grid bigger = lattice.window({3, 5, 9}, {56, 52, 50});
  for (const glm::dvec3 size : {glm::dvec3(1.5, 2.0, 1.0), glm::dvec3(9.0, 8.0, 7.0)}) {
    const glm::dvec3 at(0.7, -0.4, 0.3);
    const auto onA = sampleBox(a, at, size, 3);
    const auto onBigger = sampleBox(bigger, at, size, 3);
    const auto moved = rewindowLdi(onA, bigger);
    EXPECT_EQ(moved->grid, bigger);
    expectSameLdi(*wholeLdi(moved), *wholeLdi(onBigger), "onto the larger window");
    expectSameLdi(*wholeLdi(rewindowLdi(onBigger, a)), *wholeLdi(onA), "back onto the smaller");
    EXPECT_EQ(measureLdi(*moved).volume, measureLdi(*onBigger).volume);
  }
  // Another lattice is refused.
  Grid other = a;
  other.h *= 1.01;
  EXPECT_THROW(rewindowLdi(sampleBox(a, glm::dvec3(0.0), glm::dvec3(1.0), 1), other), Error);
}

}  // namespace
}  // namespace strata
