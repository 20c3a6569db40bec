// checkMesh measurements and prepareMesh repairs on small hand-built meshes: cubes (whole,
// open, inverted, inconsistently oriented, with a cavity), a torus for genus, a Moebius strip
// for a surface that cannot be oriented.
#include "engine/geometry/mesh_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine/util/parallel_for.h"

namespace strata {
namespace {

// Axis-aligned box [lo, hi], outward (counter-clockwise seen from outside).
TriangleMesh box(glm::dvec3 lo, glm::dvec3 hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    const int x = (i == 1 || i == 2 || i == 5 || i == 6);
    const int y = (i == 2 || i == 3 || i == 6 || i == 7);
    const int z = i >= 4;
    m.positions.push_back(lo + (hi - lo) * glm::dvec3(x, y, z));
  }
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                 {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  return m;
}

// Axis-aligned cube [lo, lo+size]^3, outward.
TriangleMesh cube(glm::dvec3 lo = glm::dvec3(0.0), double size = 1.0) {
  return box(lo, lo + glm::dvec3(size));
}

void flip(std::array<uint32_t, 3>& t) {
  std::swap(t[1], t[2]);
}

TriangleMesh inverted(TriangleMesh m) {
  for (auto& t : m.triangles) flip(t);
  return m;
}

// Appends b to a (separate shells).
void append(TriangleMesh& a, const TriangleMesh& b) {
  const uint32_t base = static_cast<uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

// Every triangle gets its own three vertices, as in STL.
TriangleMesh unindexed(const TriangleMesh& m) {
  TriangleMesh u;
  for (const auto& t : m.triangles) {
    const uint32_t base = static_cast<uint32_t>(u.positions.size());
    for (uint32_t v : t) u.positions.push_back(m.positions[v]);
    u.triangles.push_back({base, base + 1, base + 2});
  }
  return u;
}

// A torus with n x n quads (genus 1), outward.
TriangleMesh torus(int n = 12, double major = 2.0, double minor = 0.5) {
  TriangleMesh m;
  const double twoPi = 6.283185307179586;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = twoPi * i / n, v = twoPi * j / n;
      m.positions.push_back({(major + minor * std::cos(v)) * std::cos(u),
                             (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v)});
    }
  }
  auto id = [n](int i, int j) { return static_cast<uint32_t>((i % n) * n + (j % n)); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

TEST(MeshCheck, CubeIsWatertightGenusZero) {
  const MeshCheck c = checkMesh(cube());
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.vertices, 8u);
  EXPECT_EQ(c.triangles, 12u);
  EXPECT_EQ(c.components, 1);
  EXPECT_EQ(c.genus, 0);
  EXPECT_EQ(c.degenerateTriangles, 0u);
  EXPECT_DOUBLE_EQ(c.volume, 1.0);
  EXPECT_DOUBLE_EQ(c.area, 6.0);
  EXPECT_DOUBLE_EQ(c.smallestTriangleArea, 0.5);
}

// A check told to stop stops (the export's check stage honours cancel within its passes).
TEST(MeshCheck, ACancelledCheckThrows) {
  TriangleMesh many;
  for (int i = 0; i < 200; ++i) {
    const TriangleMesh c = cube(glm::dvec3(2.0 * i, 0.0, 0.0));
    const uint32_t base = uint32_t(many.positions.size());
    many.positions.insert(many.positions.end(), c.positions.begin(), c.positions.end());
    for (auto t : c.triangles) many.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  Progress running;
  EXPECT_EQ(checkMesh(many, &running).components, 200u);
  Progress cancelled;
  cancelled.cancel();
  EXPECT_THROW(checkMesh(many, &cancelled), Cancelled);
}

TEST(MeshCheck, TorusHasGenusOne) {
  const MeshCheck c = checkMesh(torus());
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.genus, 1);
  EXPECT_GT(c.volume, 0.0);
}

TEST(MeshCheck, TwoSeparateShellsAreTwoComponents) {
  TriangleMesh m = cube();
  append(m, torus());
  const MeshCheck c = checkMesh(m);
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.components, 2);
  EXPECT_EQ(c.genus, 1);
}

TEST(MeshCheck, OpenCubeHasBoundaryEdges) {
  TriangleMesh m = cube();
  m.triangles.pop_back();
  const MeshCheck c = checkMesh(m);
  EXPECT_EQ(c.boundaryEdges, 3u);
  EXPECT_FALSE(c.closed());
  EXPECT_FALSE(c.watertight());
  EXPECT_EQ(c.genus, -1);
}

TEST(MeshCheck, ThreeTrianglesOnOneEdgeAreNonManifold) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshCheck c = checkMesh(m);
  EXPECT_EQ(c.nonManifoldEdges, 1u);
  EXPECT_FALSE(c.manifold());
}

TEST(MeshCheck, OneFlippedTriangleGivesThreeMisorientedEdges) {
  TriangleMesh m = cube();
  flip(m.triangles[4]);
  const MeshCheck c = checkMesh(m);
  EXPECT_TRUE(c.closed());
  EXPECT_EQ(c.misorientedEdges, 3u);
  EXPECT_FALSE(c.oriented());
}

TEST(MeshCheck, EdgesAreCountedAfterWeldingIdenticalPositions) {
  const MeshCheck c = checkMesh(unindexed(cube()));
  EXPECT_EQ(c.vertices, 36u);
  EXPECT_TRUE(c.watertight());
  EXPECT_EQ(c.genus, 0);
}

TEST(MeshCheck, CountsDegenerateAndNonFinite) {
  TriangleMesh m = cube();
  m.positions.push_back({2, 0, 0});
  m.positions.push_back({std::numeric_limits<double>::quiet_NaN(), 6, 6});  // x left out
  m.triangles.push_back({0, 0, 1});                                         // repeated index
  m.triangles.push_back({0, 1, 8});                                         // collinear corners
  const MeshCheck c = checkMesh(m);
  EXPECT_EQ(c.degenerateTriangles, 2u);
  EXPECT_EQ(c.nonFiniteCoordinates, 1u);
  EXPECT_EQ(c.smallestTriangleArea, 0.0);
  EXPECT_FALSE(c.watertight());
}

TEST(MeshCheckPrepare, WeldsIdenticalPositions) {
  TriangleMesh m = unindexed(cube());
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.weldedVertices, 28u);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_TRUE(r.check.watertight());
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_DOUBLE_EQ(r.check.volume, 1.0);
}

TEST(MeshCheckPrepare, NegativeZeroWeldsWithZero) {
  TriangleMesh m = cube();
  m.positions.push_back({-0.0, 0.0, -0.0});
  m.triangles[0][0] = 8;  // the same corner as vertex 0
  EXPECT_EQ(weldIdenticalPositions(m), 1u);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_TRUE(checkMesh(m).watertight());
}

TEST(MeshCheckPrepare, RemovesDegenerateTriangles) {
  TriangleMesh m = cube();
  m.positions.push_back({0.5, 0, 0});  // on the edge 0-1
  m.triangles.push_back({0, 1, 1});    // repeated index
  m.triangles.push_back({0, 8, 1});    // zero area
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.removedDegenerate, 2u);
  EXPECT_EQ(r.removedUnreferenced, 1u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_TRUE(r.check.watertight());
}

TEST(MeshCheckPrepare, FlipsInvertedMesh) {
  TriangleMesh m = inverted(cube());
  ASSERT_LT(signedVolume(m), 0.0);
  const PrepareReport r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_EQ(r.reorientedTriangles, 0u);
  EXPECT_DOUBLE_EQ(r.check.volume, 1.0);
  EXPECT_TRUE(r.check.watertight());
}

TEST(MeshCheckPrepare, RepairsInconsistentOrientation) {
  TriangleMesh m = cube();
  flip(m.triangles[2]);
  flip(m.triangles[7]);
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.reorientedTriangles, 2u);
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_TRUE(r.check.watertight());
  EXPECT_DOUBLE_EQ(r.check.volume, 1.0);
}

TEST(MeshCheckPrepare, MostlyInvertedMeshIsRepairedOutward) {
  TriangleMesh m = inverted(cube());
  flip(m.triangles[5]);  // now 11 inward, 1 outward
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.reorientedTriangles, 1u);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_DOUBLE_EQ(r.check.volume, 1.0);
}

TEST(MeshCheckPrepare, CavityKeepsPointingInward) {
  TriangleMesh m = cube(glm::dvec3(0.0), 4.0);
  append(m, inverted(cube(glm::dvec3(1.0), 2.0)));
  const PrepareReport r = prepareMesh(m);
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_EQ(r.cavitiesTurnedInward, 0u);
  EXPECT_TRUE(r.check.watertight());
  EXPECT_EQ(r.check.components, 2);
  EXPECT_DOUBLE_EQ(r.check.volume, 64.0 - 8.0);
}

TEST(MeshCheckPrepare, WronglyOrientedCavityAndShellAreFixed) {
  TriangleMesh m = inverted(cube(glm::dvec3(0.0), 4.0));  // outer shell inside out
  append(m, cube(glm::dvec3(1.0), 2.0));                  // cavity pointing outward
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.shellsTurnedOutward, 1u);
  EXPECT_EQ(r.cavitiesTurnedInward, 1u);
  EXPECT_DOUBLE_EQ(r.check.volume, 64.0 - 8.0);
}

TEST(MeshCheckPrepare, ShellInsideCavityIsSolidAgain) {
  TriangleMesh m = cube(glm::dvec3(0.0), 6.0);
  append(m, cube(glm::dvec3(1.0), 4.0));  // cavity, given outward: must be flipped
  append(m, cube(glm::dvec3(2.0), 2.0));  // island inside the cavity: stays outward
  const PrepareReport r = prepareMesh(m);
  EXPECT_EQ(r.shellsTurnedOutward, 0u);
  EXPECT_EQ(r.cavitiesTurnedInward, 1u);
  EXPECT_DOUBLE_EQ(r.check.volume, 216.0 - 64.0 + 8.0);
}

// Overlapping closed shells (struts of a lattice, parts modelled as a union by winding) are not
// cavities of one another, even where one's probe point lies inside the other: a pin through a
// slab, with the pin's probe (on its longest side) inside the slab, stays outward.
TEST(MeshCheckPrepare, CrossingShellsAreNotCavities) {
  TriangleMesh m = box(glm::dvec3(0.0, 0.0, 2.0), glm::dvec3(10.0, 10.0, 8.0));  // slab
  append(m, box(glm::dvec3(4.0, 4.0, 0.0), glm::dvec3(6.0, 6.0, 10.0)));         // pin through it
  const PrepareReport r = prepareMesh(m);
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_EQ(r.check.components, 2);
  EXPECT_DOUBLE_EQ(r.check.volume, 600.0 + 40.0);
}

TEST(MeshCheckPrepare, SeparateInvertedShellsAreEachFlipped) {
  TriangleMesh m = inverted(cube());
  append(m, inverted(cube(glm::dvec3(3.0), 1.0)));
  const PrepareReport r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_DOUBLE_EQ(r.check.volume, 2.0);
}

TEST(MeshCheckPrepare, NonOrientableSurfaceIsLeftMisoriented) {
  // A Moebius strip: a band of quads whose ends are joined with a half twist.
  TriangleMesh m;
  const int n = 12;
  const double twoPi = 6.283185307179586;
  for (int i = 0; i < n; ++i) {
    const double u = twoPi * i / n;
    for (int s = -1; s <= 1; s += 2) {
      const double w = 0.3 * s;
      m.positions.push_back({(1 + w * std::cos(u / 2)) * std::cos(u),
                             (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2)});
    }
  }
  for (int i = 0; i < n; ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 1;
    uint32_t c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the twist
    m.triangles.push_back({a, c, d});
    m.triangles.push_back({a, d, b});
  }
  const PrepareReport r = prepareMesh(m);
  EXPECT_GT(r.check.misorientedEdges, 0u);
  EXPECT_GT(r.check.boundaryEdges, 0u);
  EXPECT_EQ(r.reorientedTriangles, 0u);
}

// ---- Coordinates far from 1 and far from the origin ----

TriangleMesh scaled(TriangleMesh m, double factor) {
  for (auto& p : m.positions) p *= factor;
  return m;
}

TEST(MeshCheckRange, LargestExtentOfAllOrOfTheUsedVertices) {
  EXPECT_EQ(largestExtent({}), 0.0);
  EXPECT_EQ(largestUsedExtent(TriangleMesh()), 0.0);
  TriangleMesh m = cube(glm::dvec3(5.0), 2.0);
  EXPECT_EQ(largestExtent(m.positions), 2.0);
  EXPECT_EQ(largestUsedExtent(m), 2.0);
  m.positions.push_back({1e300, 6, 6});  // used by no triangle
  EXPECT_EQ(largestExtent(m.positions), 1e300);
  EXPECT_EQ(largestUsedExtent(m), 2.0);
  m.positions.push_back({std::numeric_limits<double>::quiet_NaN(), 6, 6});  // x left out
  m.triangles.push_back({0, 1, 9});
  EXPECT_EQ(largestUsedExtent(m), 2.0);
  m.positions.push_back({-1e308, 0, 0});
  m.positions.push_back({1e308, 0, 0});
  m.triangles.push_back({0, 10, 11});
  EXPECT_TRUE(std::isinf(largestUsedExtent(m)));
}

TEST(MeshCheckRange, StrayVertexFarAwayDoesNotSpoilOrientation) {
  TriangleMesh m = inverted(cube());
  m.positions.push_back({1e20, -1e20, 0});  // used by no triangle
  const PrepareReport r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_EQ(r.removedUnreferenced, 1u);
  EXPECT_EQ(r.check.volume, 1.0);
}

TEST(MeshCheckRange, HugeCubeIsNeitherFlippedNorDegenerate) {
  // Its volume (1e600) and area do not fit a double: they are +inf, but the orientation and
  // the degeneracy tests are right.
  TriangleMesh m = cube(glm::dvec3(0.0), 1e200);
  PrepareReport r = prepareMesh(m);
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_EQ(r.removedDegenerate, 0u);
  EXPECT_TRUE(r.check.watertight());
  EXPECT_EQ(r.check.degenerateTriangles, 0u);
  EXPECT_EQ(r.check.volume, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.check.area, std::numeric_limits<double>::infinity());

  m = inverted(cube(glm::dvec3(0.0), 1e200));
  r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_NEAR(checkMesh(scaled(m, 1e-200)).volume, 1.0, 1e-12);
}

TEST(MeshCheckRange, TinyCubeIsNeitherFlippedNorDegenerate) {
  // Its volume (1e-600) underflows to 0, but the orientation and degeneracy tests are right.
  TriangleMesh m = cube(glm::dvec3(0.0), 1e-200);
  PrepareReport r = prepareMesh(m);
  EXPECT_FALSE(r.flippedInsideOut());
  EXPECT_EQ(r.removedDegenerate, 0u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_TRUE(r.check.watertight());
  EXPECT_EQ(r.check.volume, 0.0);

  m = inverted(cube(glm::dvec3(0.0), 1e-200));
  r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_NEAR(checkMesh(scaled(m, 1e200)).volume, 1.0, 1e-12);

  m = cube(glm::dvec3(0.0), 1e-200);
  m.positions.push_back({0.5e-200, 0, 0});  // on the edge 0-1: still degenerate at this scale
  m.triangles.push_back({0, 8, 1});
  r = prepareMesh(m);
  EXPECT_EQ(r.removedDegenerate, 1u);
}

TEST(MeshCheckRange, NestedShellsAtHugeScale) {
  TriangleMesh m = inverted(cube(glm::dvec3(0.0), 4e200));  // outer shell inside out
  append(m, cube(glm::dvec3(1e200), 2e200));                // cavity pointing outward
  const PrepareReport r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_NEAR(checkMesh(scaled(m, 1e-200)).volume, 64.0 - 8.0, 1e-9);
}

TEST(MeshCheckRange, CubeFarFromTheOrigin) {
  // About the origin, a unit cube at 1e15 sums terms of 1e45 to a volume of 1: noise.
  const glm::dvec3 far(1e15, -3e15, 2e15);
  EXPECT_EQ(checkMesh(cube(far)).volume, 1.0);
  EXPECT_EQ(checkMesh(cube(far)).area, 6.0);
  TriangleMesh m = cube(far);
  EXPECT_FALSE(prepareMesh(m).flippedInsideOut());
  m = inverted(cube(far));
  const PrepareReport r = prepareMesh(m);
  EXPECT_TRUE(r.flippedInsideOut());
  EXPECT_EQ(r.check.volume, 1.0);
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// Many shells, unwelded (every triangle with corners of its own, as STL lists them), in a
// shuffled order, with a few defects: more triangles than one parallel chunk (65536), so the
// parallel weld, edge sort and union-find run on several threads.
TriangleMesh manyUnweldedShells() {
  TriangleMesh indexed;
  for (int i = 0; i < 6400; ++i) {
    TriangleMesh c = cube(glm::dvec3(2.0 * (i % 80), 2.0 * (i / 80), 0.0), 1.0 + 0.001 * (i % 7));
    const uint32_t base = uint32_t(indexed.positions.size());
    indexed.positions.insert(indexed.positions.end(), c.positions.begin(), c.positions.end());
    for (auto t : c.triangles) indexed.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  flip(indexed.triangles[12 * 17 + 3]);                          // a misoriented triangle
  indexed.triangles.erase(indexed.triangles.begin() + 12 * 40);  // an open cube
  TriangleMesh m;
  uint64_t state = 12345;
  std::vector<size_t> order(indexed.triangles.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (size_t i = order.size() - 1; i > 0; --i) {  // a fixed shuffle
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    std::swap(order[i], order[size_t(state >> 33) % (i + 1)]);
  }
  for (size_t t : order) {
    const uint32_t base = uint32_t(m.positions.size());
    for (uint32_t v : indexed.triangles[t]) m.positions.push_back(indexed.positions[v]);
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

TEST(MeshCheck, TheSameOnOneThreadAndOnMany) {
  const TriangleMesh m = manyUnweldedShells();
  setWorkerCount(1);
  const MeshCheck one = checkMesh(m);
  setWorkerCount(8);
  const MeshCheck many = checkMesh(m);
  setWorkerCount(0);
  EXPECT_EQ(one.triangles, 6400u * 12 - 1);
  EXPECT_EQ(one.components, 6400);
  EXPECT_EQ(one.boundaryEdges, 3u);
  EXPECT_EQ(one.misorientedEdges, 3u);
  EXPECT_EQ(many.components, one.components);
  EXPECT_EQ(many.boundaryEdges, one.boundaryEdges);
  EXPECT_EQ(many.nonManifoldEdges, one.nonManifoldEdges);
  EXPECT_EQ(many.misorientedEdges, one.misorientedEdges);
  EXPECT_EQ(many.genus, one.genus);
  EXPECT_EQ(many.volume, one.volume);  // fixed blocks added in order: the same bits
  EXPECT_EQ(many.area, one.area);
}

// 6000 closed cubes on a diagonal, each touching the next at one corner (one vertex after
// welding, in two components), then a torus: more triangles than one block of the check's
// passes, and vertices that belong to two components (counted once in each for the genus).
TEST(MeshCheck, ShellsTouchingAtCornersKeepTheirOwnGenus) {
  TriangleMesh m;
  for (int i = 0; i < 6000; ++i) append(m, cube(glm::dvec3(double(i)), 1.0));
  append(m, torus());
  for (const int threads : {1, 8}) {
    setWorkerCount(threads);
    const MeshCheck c = checkMesh(m);
    EXPECT_TRUE(c.watertight()) << threads;
    EXPECT_EQ(c.triangles, 6000u * 12 + torus().triangles.size()) << threads;
    EXPECT_EQ(c.components, 6001) << threads;
    EXPECT_EQ(c.genus, 1) << threads;  // each cube's shared corners counted in each cube
  }
  setWorkerCount(0);
}

TEST(MeshCheck, WeldingOnManyThreadsKeepsTheFirstVertexOfEachPosition) {
  TriangleMesh m = manyUnweldedShells();
  const size_t before = m.positions.size();
  setWorkerCount(8);
  const size_t merged = weldIdenticalPositions(m);
  setWorkerCount(0);
  EXPECT_EQ(before - merged, 6400u * 8);  // eight corners a cube
  EXPECT_EQ(m.positions.size(), 6400u * 8);
  const MeshCheck c = checkMesh(m);
  EXPECT_EQ(c.components, 6400);
}

}  // namespace
}  // namespace strata
