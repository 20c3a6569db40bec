// The editor's splats (engine/ldi/splats.h), also what the point cloud writer writes: every
// surfel once, on its dominant axis, at its exact position, carrying its normal and leaf.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstring>

#include "engine/eval/cpu_backend.h"
#include "engine/ldi/splats.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

TEST(Splats, OneSplatPerSurfelOnItsDominantAxis) {
  Scene scene =
      makeScene(op(NodeKind::Union, {sphere(1.0), box(glm::dvec3(1.0), {1.2, 0, 0})}), 40);
  EvalResult result = evaluateCpu(scene);
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  SplatsHandle handle = backend->splats(result.root, progress);
  ASSERT_TRUE(handle);
  ASSERT_NE(handle->hostData(), nullptr);  // the CPU backend keeps them on the host
  std::vector<Splat> copied(handle->count());
  handle->copyToHost(copied.data());

  std::shared_ptr<const Ldi> host = backend->download(result.root);
  SplatLevels levels;
  std::vector<Splat> built = buildSplats(*host, &levels);
  ASSERT_EQ(built.size(), copied.size());
  const SplatLevels handed = handle->levels();
  for (int level = 0; level < kSplatLevels; ++level)
    EXPECT_EQ(handed.end[level], levels.end[level]) << level;
  // The reference, written out here: every surfel on its dominant axis, at origin + h * (global
  // node line, depth); first the rays whose two global node lines are both multiples of 4, then
  // of 2, then the others; within each, in axis, ray, depth order.
  size_t i = 0;
  const Grid& g = host->grid;
  auto multipleOf = [](int64_t line, int64_t m) { return ((line % m) + m) % m == 0; };
  for (int level = kSplatLevels - 1; level >= 0; --level) {
    const uint64_t start = level + 1 < kSplatLevels ? levels.end[level + 1] : 0;
    EXPECT_EQ(i, start) << "level " << level << " starts where the coarser one ends";
    for (int axis = 0; axis < 3; ++axis) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const AxisLdi& a = host->axes[axis];
      for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray) {
        const int64_t lu = g.first[u] + ray % g.raysU(axis), lv = g.first[v] + ray / g.raysU(axis);
        const int64_t step = int64_t(1) << level;
        const bool atLevel =
            multipleOf(lu, step) && multipleOf(lv, step) &&
            (level == kSplatLevels - 1 || !(multipleOf(lu, 2 * step) && multipleOf(lv, 2 * step)));
        if (!atLevel) continue;
        for (uint32_t k = a.offsets[size_t(ray)]; k < a.offsets[size_t(ray) + 1]; ++k) {
          const Surfel& s = a.surfels[k];
          float n[3];
          decodeNormal(s.normal, n);
          if (!onDominantAxis(n, axis)) continue;
          ASSERT_LT(i, built.size());
          glm::dvec3 p;
          p[axis] = g.origin[axis] + g.h * double(s.depth);
          p[u] = g.origin[u] + g.h * double(g.first[u] + ray % g.raysU(axis));
          p[v] = g.origin[v] + g.h * double(g.first[v] + ray / g.raysU(axis));
          const Splat& splat = built[i];
          EXPECT_EQ(splat.leafAxis & 3u, uint32_t(axis));
          EXPECT_EQ(splatLeaf(splat), surfelLeaf(s.tag));
          EXPECT_EQ(splat.normal, s.normal);
          EXPECT_EQ(splat.position[0], float(p.x));
          EXPECT_EQ(splat.position[1], float(p.y));
          EXPECT_EQ(splat.position[2], float(p.z));
          EXPECT_EQ(std::memcmp(&splat, &copied[i], sizeof(Splat)), 0);
          ++i;
        }
      }
    }
    EXPECT_EQ(i, levels.end[level]) << "level " << level << " ends";
  }
  EXPECT_EQ(i, built.size());
  // Each coarser level holds about a quarter of the splats of the next finer one.
  for (int level = 1; level < kSplatLevels; ++level) {
    EXPECT_GT(double(levels.end[level]), 0.15 * double(levels.end[level - 1])) << level;
    EXPECT_LT(double(levels.end[level]), 0.40 * double(levels.end[level - 1])) << level;
  }
  // A curved patch is sampled on all three axes and becomes splats on one; the box's faces are
  // sampled on one axis only.
  EXPECT_GT(double(built.size()), 0.3 * double(host->surfelCount()));
  EXPECT_LT(built.size(), host->surfelCount());
  // Splats lie on the surface they came from: the sphere's within a cell of radius 1.
  for (const Splat& s : built) {
    const glm::dvec3 p(s.position[0], s.position[1], s.position[2]);
    if (p.x < 0.0) {
      EXPECT_NEAR(glm::length(p), 1.0, result.grid.h);
    }
  }
}

// The editor's Diagnostics said "60 x 41 x 32" for a bracket exported at 60 x 40 x 30: it gave
// the tree's bounds (a turned part's box). The result's box from its splats: a turned cube's is
// the turned cube's (its corners), not the box of the unturned one around it, within a cell.
TEST(Splats, TheirBoxIsTheResultsExtent) {
  Transform turned;
  turned.rotateDegrees = {0.0, 0.0, 45.0};
  NodePtr cube = withTransform(box(glm::dvec3(1.0)), turned);
  Scene scene = makeScene(op(NodeKind::Difference, {cube, box({2.0, 2.0, 1.0}, {0, 0, 0.75})}), 64);
  EvalResult result = evaluateCpu(scene);
  auto backend = std::make_shared<CpuBackend>();
  Progress progress;
  SplatsHandle handle = backend->splats(result.root, progress);
  const Bounds b = splatBounds(*handle);
  const double h = result.grid.h;
  const double half = std::sqrt(0.5);  // the turned cube's corner, from its centre
  EXPECT_NEAR(b.max.x, half, h);
  EXPECT_NEAR(b.min.y, -half, h);
  EXPECT_NEAR(b.max.z, 0.25, 1e-6);  // the cut's flat face, on a ray: exact
  EXPECT_NEAR(b.min.z, -0.5, 1e-6);
  EXPECT_TRUE(splatBounds(HostSplats({})).empty());
}

TEST(Splats, EmptyLdiHasNone) {
  Grid grid;
  grid.cells = glm::ivec3(8);
  EXPECT_TRUE(buildSplats(*makeEmptyLdi(grid)).empty());
}

// Arrays handed back by released host splats are reused by the next take that they hold (no
// new memory), at most kKept of them, the largest kept.
TEST(SplatArrayPool, ReleasedArraysAreReused) {
  auto pool = std::make_shared<SplatArrayPool>();
  std::vector<Splat> first = pool->take(1000);
  ASSERT_EQ(first.size(), 1000u);
  const Splat* memory = first.data();
  {
    HostSplats held(std::move(first), SplatLevels::flat(1000), pool);
    EXPECT_EQ(held.count(), 1000u);
    EXPECT_EQ(held.hostData(), memory);
  }  // released: back to the pool
  std::vector<Splat> again = pool->take(800);
  EXPECT_EQ(again.data(), memory) << "the released array, not new memory";
  EXPECT_EQ(again.size(), 800u);
  std::vector<Splat> larger = pool->take(5000);  // nothing kept holds it: new memory
  EXPECT_NE(larger.data(), memory);
  // Three given back, two kept: the largest two.
  std::vector<Splat> small(10), medium(100), big(10000);
  const Splat* mediumMemory = medium.data();
  const Splat* bigMemory = big.data();
  pool->give(std::move(small));
  pool->give(std::move(medium));
  pool->give(std::move(big));
  EXPECT_EQ(pool->take(50).data(), mediumMemory);
  EXPECT_EQ(pool->take(50).data(), bigMemory);
}

}  // namespace
}  // namespace strata::test
