// CPU sampling: watertight on real meshes, and a tile (window) of the grid sees exactly the
// surfels the whole grid sees on the same rays.
#include <gtest/gtest.h>

#include "engine/ldi/combine_ldi.h"
#include "engine/ldi/sample_mesh.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

TEST(SampleMesh, EveryRayOfAClosedMeshHasAnEvenCleanList) {
  auto mesh = dataMesh("knot1.obj");
  Grid grid = makeGrid(meshBounds(*mesh), 128, 0.05);
  auto ldi = sampleMesh(*mesh, glm::dmat4(1.0), grid, 7);
  size_t total = 0;
  for (int a = 0; a < 3; ++a) {
    const AxisLdi& axis = ldi->axes[a];
    for (size_t r = 0; r + 1 < axis.offsets.size(); ++r) {
      uint32_t b = axis.offsets[r], e = axis.offsets[r + 1];
      ASSERT_EQ((e - b) % 2, 0u);
      for (uint32_t k = b; k < e; ++k) {
        EXPECT_EQ(surfelEnters(axis.surfels[k].tag), (k - b) % 2 == 0);
        EXPECT_EQ(surfelLeaf(axis.surfels[k].tag), 7u);
        if (k > b) {
          EXPECT_LE(axis.surfels[k - 1].depth, axis.surfels[k].depth);
        }
      }
    }
    total += axis.surfels.size();
  }
  EXPECT_GT(total, 10000u);
}

TEST(SampleMesh, WindowMatchesTheWholeGridOnItsRays) {
  auto mesh = dataMesh("bunny.obj");
  Grid grid = makeGrid(meshBounds(*mesh), 96, 0.05);
  auto whole = wholeLdi(sampleMesh(*mesh, glm::dmat4(1.0), grid, 1));
  const glm::ivec3 start(17, 30, 21), count(40, 33, 29);
  Grid tile = grid.window(start, count);
  auto part = wholeLdi(sampleMesh(*mesh, glm::dmat4(1.0), tile, 1));
  int compared = 0;
  for (int a = 0; a < 3; ++a) {
    const int u = grid.uAxis(a), v = grid.vAxis(a);
    for (int j = 0; j < tile.raysV(a); ++j)
      for (int i = 0; i < tile.raysU(a); ++i) {
        int64_t wholeRay = int64_t(start[u] + i) + int64_t(start[v] + j) * grid.raysU(a);
        int64_t tileRay = int64_t(i) + int64_t(j) * tile.raysU(a);
        auto inside = [&](const Ldi& l, int64_t ray) {
          std::vector<Surfel> s;
          const AxisLdi& ax = l.axes[a];
          for (uint32_t k = ax.offsets[size_t(ray)]; k < ax.offsets[size_t(ray) + 1]; ++k)
            if (ax.surfels[k].depth > start[a] && ax.surfels[k].depth < start[a] + count[a])
              s.push_back(ax.surfels[k]);
          return s;
        };
        auto x = inside(*whole, wholeRay), y = inside(*part, tileRay);
        ASSERT_EQ(x.size(), y.size()) << "axis " << a << " ray " << i << "," << j;
        for (size_t k = 0; k < x.size(); ++k) {
          EXPECT_EQ(x[k].depth, y[k].depth);
          EXPECT_EQ(x[k].normal, y[k].normal);
          EXPECT_EQ(x[k].tag, y[k].tag);
          ++compared;
        }
      }
  }
  EXPECT_GT(compared, 1000);
}

// An open mesh (taken with --allow-open or marked open): rays through its holes leave the
// winding unbalanced and were taken as inside up to the grid's end, streaks of solid far from
// the part (an artist's holey scan, imported "anyway"). Such rays are left empty; every other
// ray is the closed mesh's, and nothing lies beyond the part.
TEST(SampleMesh, RaysThroughTheHolesOfAnOpenMeshAreLeftEmptyNotStreaked) {
  auto closed = dataMesh("bunny.obj");
  auto open = withHoles(*closed, 400);
  const Bounds bounds = meshBounds(*closed);
  Grid grid = makeGrid(bounds, 96, 0.25);
  auto a = sampleMesh(*closed, glm::dmat4(1.0), grid, 1);
  auto b = sampleMesh(*open, glm::dmat4(1.0), grid, 1);
  size_t rays = 0, emptied = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const AxisLdi& x = a->axes[axis];
    const AxisLdi& y = b->axes[axis];
    ASSERT_EQ(x.offsets.size(), y.offsets.size());
    // The part's extent along the axis in grid units, one cell to spare.
    const double lo = (bounds.min[axis] - grid.origin[axis]) / grid.h - 1.0;
    const double hi = (bounds.max[axis] - grid.origin[axis]) / grid.h + 1.0;
    for (size_t r = 0; r + 1 < y.offsets.size(); ++r) {
      for (uint32_t k = y.offsets[r]; k < y.offsets[r + 1]; ++k) {
        ASSERT_GE(y.surfels[k].depth, lo) << "axis " << axis << " ray " << r;
        ASSERT_LE(y.surfels[k].depth, hi) << "axis " << axis << " ray " << r;
      }
      const uint32_t n = x.offsets[r + 1] - x.offsets[r];
      const uint32_t m = y.offsets[r + 1] - y.offsets[r];
      rays += n > 0;
      if (n > 0 && m == 0) ++emptied;
      ASSERT_EQ(m % 2, 0u);
    }
  }
  EXPECT_GT(emptied, 0u) << "the holes were met";
  EXPECT_LT(emptied * 100, rays) << "fewer than 1% of the part's rays";
}

TEST(SampleMesh, RejectsGeometryAtAbsurdDistances) {
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1e30, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  Grid grid = makeGrid(Bounds{{0, 0, 0}, {1, 1, 1}}, 16, 0.0);
  EXPECT_THROW(sampleMesh(mesh, glm::dmat4(1.0), grid, 1), Error);
}

}  // namespace
}  // namespace strata::test
