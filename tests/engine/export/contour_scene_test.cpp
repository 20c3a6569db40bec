// Watertight export by dual contouring: invariants, volumes, topology (genus and components),
// sharp features, and tiled == untiled.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/contour_scene.h"
#include "engine/io/scene_file.h"
#include "engine/ldi/offset_math.h"
#include "tests/support/export_cases.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {
constexpr double kPi = 3.14159265358979323846;

struct Contoured {
  ExportMesh mesh;
  ContourReport report;
  MeshCheck check;
};

Contoured contour(const Scene& scene, int tileCells = 256) {
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  Contoured c;
  c.mesh = contourScene(scene, evaluator, ContourOptions{0, tileCells}, progress, &c.report);
  c.check = checkMesh(c.mesh.mesh);
  return c;
}

struct Case {
  const char* name;
  NodePtr root;
  double volume;
  double boundArea;  // upper bound of the surface area, for the volume tolerance
  int genus;         // -1: not checked
  int components;
};

std::vector<Case> analyticCases() {
  double ball = 4.0 / 3.0 * kPi * 1.2 * 1.2 * 1.2;
  double cap = kPi * 0.2 * 0.2 * (3 * 1.2 - 0.2) / 3;
  return {
      {"sphere_union", op(NodeKind::Union, {sphere(1.0, {-0.5, 0, 0}), sphere(1.0, {0.5, 0, 0})}),
       9 * kPi / 4, 8 * kPi, 0, 1},
      {"sphere_intersection",
       op(NodeKind::Intersection, {sphere(1.0, {-0.5, 0, 0}), sphere(1.0, {0.5, 0, 0})}),
       5 * kPi / 12, 8 * kPi, 0, 1},
      {"sphere_difference",
       op(NodeKind::Difference, {sphere(1.0, {-0.5, 0, 0}), sphere(1.0, {0.5, 0, 0})}),
       11 * kPi / 12, 8 * kPi, 0, 1},
      {"steinmetz",
       op(NodeKind::Intersection, {cylinder(1.0, 3.0, {}, {0, 90, 0}),
                                   cylinder(1.0, 3.0, {}, {90, 0, 0}), cylinder(1.0, 3.0)}),
       8 * (2 - std::sqrt(2.0)), 3 * (2 * kPi * 3 + 2 * kPi), 0, 1},
      {"cube_minus_ball", op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}),
       8 - (ball - 6 * cap), 24 + 4 * kPi * 1.44, 5, 1},
      {"torus_half", op(NodeKind::Intersection, {torus(1.0, 0.25), box({4, 4, 1}, {0, 0, 0.5})}),
       kPi * kPi * 0.25 * 0.25, 4 * kPi * kPi * 0.25 + 2 * kPi, 1, 1},
      {"box_with_cavity", op(NodeKind::Difference, {box({2, 2, 2}), sphere(0.6)}),
       8 - 4.0 / 3.0 * kPi * 0.216, 24 + 4 * kPi * 0.36, -1, 2},
      {"disjoint_spheres", op(NodeKind::Union, {sphere(0.5, {-1, 0, 0}), sphere(0.5, {1, 0, 0})}),
       2 * 4.0 / 3.0 * kPi * 0.125, 2 * kPi, 0, 2},
  };
}

class ContourAnalytic : public ::testing::TestWithParam<int> {};

TEST_P(ContourAnalytic, WatertightWithVolumeAndTopology) {
  for (const Case& c : analyticCases()) {
    Contoured r = contour(makeScene(c.root, GetParam()));
    EXPECT_TRUE(isWatertight(r.mesh.mesh)) << c.name;
    EXPECT_NEAR(r.check.volume, c.volume, 0.25 * r.report.grid.h * c.boundArea) << c.name;
    EXPECT_EQ(r.check.components, c.components) << c.name;
    // Thick shapes never fold; the cavity's shell keeps its negative volume.
    EXPECT_EQ(r.report.unfoldedShells, 0) << c.name;
    if (c.genus >= 0) {
      EXPECT_EQ(r.check.genus, c.genus) << c.name;
    }
    EXPECT_EQ(r.mesh.triangleLeaf.size(), r.mesh.mesh.triangles.size());
    for (uint32_t leaf : r.mesh.triangleLeaf) ASSERT_TRUE(r.mesh.leaves.count(leaf)) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Resolutions, ContourAnalytic, ::testing::Values(64, 128));

TEST(ContourTopology, MengerSpongeLevelTwoHasGenus81AndExactVolume) {
  // 20 x 20 = 400 cubes of side 1/9 (level 2), united; all faces lie on grid planes.
  std::vector<NodePtr> cubes;
  auto solid = [](int x, int y, int z) {
    for (int level = 0; level < 2; ++level) {
      int holes = (x % 3 == 1) + (y % 3 == 1) + (z % 3 == 1);
      if (holes >= 2) return false;
      x /= 3;
      y /= 3;
      z /= 3;
    }
    return true;
  };
  for (int x = 0; x < 9; ++x)
    for (int y = 0; y < 9; ++y)
      for (int z = 0; z < 9; ++z)
        if (solid(x, y, z))
          cubes.push_back(box(glm::dvec3(1.0 / 9), (glm::dvec3(x, y, z) + 0.5) / 9.0));
  ASSERT_EQ(cubes.size(), 400u);
  auto root = std::make_shared<Node>(*op(NodeKind::Union, {}));
  root->children = cubes;
  const double exact = (20.0 / 27.0) * (20.0 / 27.0);
  for (int resolution : {33, 66}) {  // h = 1/27 and 1/54: every cube face on grid planes
    Scene s = makeSceneInBox(root, resolution, glm::dvec3(-1.0 / 9), glm::dvec3(1 + 1.0 / 9));
    EvalResult e = evaluateCpu(s);
    EXPECT_NEAR(e.measure.volume, exact, 1e-12) << resolution;
    Contoured r = contour(s);
    EXPECT_TRUE(isWatertight(r.mesh.mesh));
    EXPECT_EQ(r.check.genus, 81) << resolution;
    EXPECT_EQ(r.check.components, 1);
    // Vertices sit on the faces up to the cell margin that keeps them inside their cells.
    EXPECT_NEAR(r.check.volume, exact, 2e-3 * r.report.grid.h * 40.0) << resolution;
  }
}

// Distance from p to the surface of an axis-aligned box centred at the origin (half sizes b).
double boxSurfaceDistance(const glm::dvec3& p, const glm::dvec3& b) {
  glm::dvec3 q = glm::abs(p) - b;
  double outside = glm::length(glm::max(q, glm::dvec3(0.0)));
  double inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
  return std::fabs(outside + inside);
}

// Distances of the output vertices from the exact surface, in cells, sorted.
std::vector<double> sortedDistances(const ExportMesh& mesh, double h,
                                    const std::function<double(const glm::dvec3&)>& distance) {
  std::vector<double> d;
  for (const auto& p : mesh.mesh.positions) d.push_back(distance(p) / h);
  std::sort(d.begin(), d.end());
  return d;
}

// Measured (see tests/bench/RESULTS.md): the median vertex lies within 0.001 h of the exact
// surface, 99% within 0.07 h, the worst (next to a corner, where the vertex must stay in its
// cell) within 0.31 h at both resolutions. Asserted with a little room.
TEST(ContourSharpFeatures, RotatedBoxCornersAndEdgesAreRecovered) {
  Transform t;
  t.translate = {0.0123, -0.0371, 0.0217};
  t.rotateDegrees = {17, 29, 41};
  NodePtr b = withTransform(box({1.0, 0.8, 0.6}), t);
  const glm::dmat4 toLocal = glm::inverse(t.matrix());
  for (int resolution : {64, 128}) {
    Contoured r = contour(makeScene(b, resolution));
    ASSERT_TRUE(isWatertight(r.mesh.mesh));
    const double h = r.report.grid.h;
    auto d = sortedDistances(r.mesh, h, [&](const glm::dvec3& p) {
      return boxSurfaceDistance(glm::dvec3(toLocal * glm::dvec4(p, 1.0)), {0.5, 0.4, 0.3});
    });
    EXPECT_LT(d[d.size() / 2], 0.001) << resolution;
    EXPECT_LT(d[d.size() * 99 / 100], 0.1) << resolution;
    EXPECT_LT(d.back(), 0.4) << resolution;
    // Each of the eight corners has a vertex within the corner cell's reach.
    for (int k = 0; k < 8; ++k) {
      glm::dvec3 corner((k & 1) ? 0.5 : -0.5, (k & 2) ? 0.4 : -0.4, (k & 4) ? 0.3 : -0.3);
      glm::dvec3 world = glm::dvec3(t.matrix() * glm::dvec4(corner, 1.0));
      double nearest = 1e9;
      for (const auto& p : r.mesh.mesh.positions)
        nearest = std::min(nearest, glm::length(p - world));
      EXPECT_LT(nearest / h, 0.5) << "corner " << k << " at " << resolution;
    }
  }
}

TEST(ContourSharpFeatures, BoxMinusCylinderOffTheGrid) {
  NodePtr b = box({1.0, 1.0, 0.5}, {0.013, 0.029, -0.017});
  auto c = std::make_shared<Node>(*cylinder(0.3, 1.0, {0.113, 0.071, 0.0}));
  c->params.segments = 512;  // tessellation error far below h
  Contoured r = contour(makeScene(op(NodeKind::Difference, {b, c}), 96));
  ASSERT_TRUE(isWatertight(r.mesh.mesh));
  EXPECT_EQ(r.check.genus, 1);
  auto d = sortedDistances(r.mesh, r.report.grid.h, [](const glm::dvec3& p) {
    double dBox = boxSurfaceDistance(p - glm::dvec3(0.013, 0.029, -0.017), {0.5, 0.5, 0.25});
    glm::dvec3 q = p - glm::dvec3(0.113, 0.071, 0.0);
    double dCyl = std::fabs(std::sqrt(q.x * q.x + q.y * q.y) - 0.3);
    return std::min(dBox, dCyl);  // every vertex lies near the box's faces or the drilled wall
  });
  EXPECT_LT(d[d.size() / 2], 0.01);
  EXPECT_LT(d[d.size() * 99 / 100], 0.1);
  EXPECT_LT(d.back(), 0.4);
}

TEST(ContourTiling, TiledAndUntiledAreIdenticalOnTheArmadillo) {
  auto mesh = dataMesh("armadillo.obj");
  Scene s = makeScene(meshLeaf(mesh), 512);
  Contoured whole = contour(s, 512);
  Contoured tiled = contour(s, 96);
  EXPECT_EQ(whole.report.tiles, 1);
  EXPECT_GT(tiled.report.tiles, 8);
  ASSERT_EQ(whole.mesh.mesh.positions.size(), tiled.mesh.mesh.positions.size());
  ASSERT_EQ(whole.mesh.mesh.triangles.size(), tiled.mesh.mesh.triangles.size());
  EXPECT_TRUE(whole.mesh.mesh.positions == tiled.mesh.mesh.positions);
  EXPECT_TRUE(whole.mesh.mesh.triangles == tiled.mesh.mesh.triangles);
  EXPECT_TRUE(whole.mesh.triangleLeaf == tiled.mesh.triangleLeaf);
  EXPECT_TRUE(isWatertight(whole.mesh.mesh));
  EXPECT_EQ(whole.check.genus, 0);
}

TEST(ContourRealMeshes, GenusAndVolumeOfDataMeshes) {
  struct M {
    const char* file;
    int genus;
    double volume;
  };
  for (M m : {M{"eight.obj", 2, 0.0401729}, M{"knot1.obj", 1, 0.0951747},
              M{"bunny.obj", 0, 194.288371812}, M{"fandisk.obj", 0, 0.14036}}) {
    auto mesh = dataMesh(m.file);
    double area = surfaceArea(*mesh);
    for (int resolution : {96, 160}) {
      Contoured r = contour(makeScene(meshLeaf(mesh), resolution));
      EXPECT_TRUE(isWatertight(r.mesh.mesh)) << m.file << " " << resolution;
      EXPECT_EQ(r.check.genus, m.genus) << m.file << " " << resolution;
      EXPECT_NEAR(r.check.volume, m.volume, 0.25 * r.report.grid.h * area) << m.file;
    }
  }
}

TEST(ContourScene, CancelledExportThrows) {
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  progress.cancel();
  EXPECT_THROW(contourScene(makeScene(sphere(1.0), 64), evaluator, ContourOptions{}, progress),
               Cancelled);
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

// Regression: in the bone scaffold of scaled copies (the bundled scaffold before it had a true
// offset) with its offset moved by a fraction of a cell, two surface
// components of one cell had their vertices clamped to the same corner; welded by position the
// mesh was pinched there. Every vertex must have its own position.
TEST(ContourRegression, ScaffoldWithMovedOffsetHasNoPinchedVertices) {
  Scene s = loadScene(assetsDir() + "/scenes/bone_scaffold_scaled_copy.strata.json");
  const Grid grid = Evaluator::gridFor(s, 256);
  auto root = std::make_shared<Node>(*s.root);
  for (auto& child : root->children) {
    if (child->name != "cortical shell") continue;
    auto offset = std::make_shared<Node>(*child->children[1]);
    offset->transform.translate += glm::dvec3(0.37 * grid.h);
    auto shell = std::make_shared<Node>(*child);
    shell->children[1] = offset;
    child = shell;
  }
  s.root = root;
  s.settings.resolution = 256;
  Contoured r = contour(s);
  EXPECT_TRUE(isWatertight(r.mesh.mesh));
  EXPECT_TRUE(r.check.manifold());  // checkMesh welds identical positions first
}

// The folded sliver (tests/support/export_cases.h): its shell turned inside out (volume
// -5.6e-6 mm^3: a void to a slicer) is pulled back towards its cell centres.
TEST(ContourRegression, FoldedSliverShellIsTurnedRightSideOut) {
  Contoured r = contour(makeScene(foldedSliver(), 8), 8);
  EXPECT_TRUE(isWatertight(r.mesh.mesh));
  EXPECT_EQ(r.report.unfoldedShells, 1);
  EXPECT_GT(r.check.volume, 0.0);
  EXPECT_EQ(r.check.degenerateTriangles, 0u);
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

Grid cubeGrid(int cells) {
  Grid g;
  g.cells = glm::ivec3(cells);
  g.h = 1.0;
  return g;
}

// Bytes of the contouring arrays of one tile of `tile` cells on a grid of `cells` a side.
uint64_t tileArrayBytes(int tile, int cells) {
  const uint64_t side = uint64_t(std::min(tile, cells) + 3);
  return side * side * side * kContourBytesPerNode;
}

TEST(ExportTiles, AsFewAsMemoryAllowsAndNeverLargerThanTheLimit) {
  const uint64_t plenty = uint64_t(1) << 40;
  EXPECT_EQ(exportTileCells(cubeGrid(512), plenty), 512);  // one tile
  EXPECT_EQ(exportTileCells(cubeGrid(1000), plenty), 1000);
  EXPECT_EQ(exportTileCells(cubeGrid(2048), plenty), 1024);  // 8 tiles
  EXPECT_EQ(exportTileCells(cubeGrid(1536), plenty), 768);
  EXPECT_EQ(exportTileCells(cubeGrid(512), 0), 256);  // memory unknown: the old default
  // Just too little memory for one tile of 512: two parts a side.
  const uint64_t budget = 4 * tileArrayBytes(512, 512) - 1;
  EXPECT_EQ(exportTileCells(cubeGrid(512), budget), 256);
  EXPECT_LE(4 * tileArrayBytes(256, 512), budget);
  // Almost nothing: the smallest tile.
  EXPECT_EQ(exportTileCells(cubeGrid(512), 1), 8);
  // A flat grid: the short sides bound the arrays.
  Grid flat = cubeGrid(1024);
  flat.cells.z = 16;
  EXPECT_EQ(exportTileCells(flat, 4 * tileArrayBytes(1024, 1024) / 40), 1024);
}

// With modifiers the offsets' arrays of a tile's grown window must fit, at the bytes a node of
// the backend that runs them: the CPU's 17 (engine/ldi/offset_ldi.h) take one tile where the
// device's 40 would take several, each evaluated on its grown window (a rounded part at 1024
// cells took four tiles and 2.7 times the grid's nodes on the CPU).
TEST(ExportTiles, ModifierTilesAreSizedByTheBackendsOffsetBytes) {
  const double nodes = 515.0 * 515.0 * 515.0;  // one tile of the whole grid, grown and clipped
  const uint64_t memory = uint64_t(4.0 * nodes * double(kHostOffsetBytesPerNode)) + 4;
  EXPECT_EQ(exportTileCells(cubeGrid(512), memory, 20, kHostOffsetBytesPerNode), 512);
  EXPECT_LT(exportTileCells(cubeGrid(512), memory, 20, kOffsetBytesPerNode), 512);
  EXPECT_EQ(CpuBackend().offsetBytesPerNode(), kHostOffsetBytesPerNode);
}

TEST(ExportTiles, TheDefaultTileGivesTheMeshOfAnyOtherTiling) {
  const Scene s = makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.1, {1, 1, 1})}), 40);
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourReport sized, tiled;
  const ExportMesh a = contourScene(s, evaluator, ContourOptions{}, progress, &sized);
  const ExportMesh b = contourScene(s, evaluator, ContourOptions{0, 8}, progress, &tiled);
  EXPECT_EQ(sized.tiles, 1);  // 40 cells: this machine has room for one tile
  EXPECT_EQ(sized.tileCells, 40);
  EXPECT_EQ(tiled.tiles, 125);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
}

}  // namespace
}  // namespace strata::test

namespace strata::test {
namespace {

// A modifier reads its children up to its reach away: a scene with modifiers is tiled with a
// halo of that reach (kOffsetHaloCells per offset besides), nested modifiers added up, and its
// tiles sized so that the offsets' arrays of the grown window fit. (It used to be one tile,
// refused past 2^32 cells: the bone scaffold at 4096.)
TEST(ExportTiles, ModifierScenesAreTiledWithTheirReachAround) {
  const Scene s =
      makeScene(modifier(NodeKind::Offset, 0.1, {box({2, 1, 1}), sphere(0.5, {1, 0, 0})}), 64);
  const ExportTiling t =
      exportTiling(s, ContourOptions{4096, 0}, uint64_t(1) << 40, kOffsetBytesPerNode);
  EXPECT_GT(t.count(), 1);
  EXPECT_EQ(t.halo, int(std::ceil(0.1 / t.grid.h)) + kOffsetHaloCells);
  const double window = double(t.tileCells + 2 * t.halo + 2);
  EXPECT_LE(window * window * window, double(UINT32_MAX));
  EXPECT_LE(std::pow(window + 1, 3) * double(kOffsetBytesPerNode), double(uint64_t(1) << 38));
  // Nested: a rounding (two offsets) of an offset.
  const NodePtr nested = modifier(
      NodeKind::Round, 0.05, {modifier(NodeKind::Offset, -0.1, {box({2, 1, 1})}), sphere(0.3)});
  const Grid g = Evaluator::gridFor(makeScene(nested, 256), 256);
  EXPECT_EQ(modifierHaloCells(nested, g.h),
            int(std::ceil(0.1 / g.h)) + int(std::ceil(0.1 / g.h)) + 3 * kOffsetHaloCells);
  EXPECT_EQ(modifierHaloCells(box({1, 1, 1}), g.h), 0);
  // Through an instance: an offset of an instance of a (hidden) offset adds both.
  auto inner = std::make_shared<Node>(*modifier(NodeKind::Offset, 0.2, {sphere(0.3)}));
  inner->visible = false;
  auto instance = std::make_shared<Node>();
  instance->id = 9002;
  instance->kind = NodeKind::Instance;
  instance->instanceOf = inner->id;
  const NodePtr outer = op(NodeKind::Union, {NodePtr(inner), box({1, 1, 1}),
                                             modifier(NodeKind::Offset, 0.1, {instance})});
  EXPECT_EQ(modifierHaloCells(outer, g.h),
            int(std::ceil(0.2 / g.h)) + int(std::ceil(0.1 / g.h)) + 2 * kOffsetHaloCells);
  EXPECT_TRUE(hasModifier(op(NodeKind::Union, {box({1, 1, 1}), instance, NodePtr(inner)})));
  // A reach no tile can hold beside its own cells: refused, saying why.
  const Scene huge = makeScene(modifier(NodeKind::Offset, 500.0, {box({2, 1, 1})}), 64);
  try {
    exportTiling(huge, ContourOptions{4096, 0}, uint64_t(1) << 40, kOffsetBytesPerNode);
    FAIL() << "a halo of about a million cells was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("offset, shell, round and fillet"), std::string::npos)
        << e.what();
  }
}

// A tile of a modifier scene is evaluated on its window grown by the halo and cropped back:
// the mesh is the one of a single tile, vertex for vertex, with nested modifiers (an offset
// inside a rounding) and with an offset of an instance of an offset (a halo that did not follow
// the instance would count only one of the two, and leave the tiles wrong along their seams).
TEST(ExportTiles, ATiledModifierSceneGivesTheMeshOfOneTile) {
  // At 128 cells h is about 0.02: halos of 10 to 30 cells, so tiles of 24 are evaluated on
  // windows that are only part of the grid.
  auto hidden =
      std::make_shared<Node>(*modifier(NodeKind::Offset, 0.06, {sphere(0.35, {0.9, 0.2, 0.1})}));
  hidden->visible = false;  // shown only through the instance
  const NodePtr grown = hidden;
  auto instance = std::make_shared<Node>();
  instance->id = 9001;
  instance->name = "copy";
  instance->kind = NodeKind::Instance;
  instance->instanceOf = grown->id;
  instance->transform.translate = glm::dvec3(-0.4, 0.3, 0.2);
  const NodePtr rounded =
      modifier(NodeKind::Round, 0.04,
               {op(NodeKind::Difference,
                   {modifier(NodeKind::Offset, 0.05, {box({2, 1.2, 1})}), cylinder(0.3, 3.0)})});
  const NodePtr shelled = modifier(NodeKind::Shell, 0.05, {sphere(0.4, {-0.7, 0.0, 0.5})});
  const NodePtr filleted = modifier(NodeKind::Fillet, 0.04,
                                    {op(NodeKind::Union, {box({0.5, 0.5, 0.5}, {0.6, -0.3, 0.5}),
                                                          sphere(0.3, {0.9, -0.3, 0.5})})});
  const Scene scenes[] = {
      makeScene(op(NodeKind::Union, {rounded, grown, shelled, filleted}), 128),
      makeScene(op(NodeKind::Union,
                   {box({2, 1.2, 1}), grown, modifier(NodeKind::Offset, 0.03, {instance})}),
                128),
  };
  for (const Scene& s : scenes) {
    Evaluator evaluator(std::make_shared<CpuBackend>());
    Progress progress;
    ContourReport one, tiled;
    const ExportMesh a = contourScene(s, evaluator, ContourOptions{0, 0}, progress, &one);
    const ExportMesh b = contourScene(s, evaluator, ContourOptions{0, 24}, progress, &tiled);
    EXPECT_EQ(one.tiles, 1);
    EXPECT_GT(tiled.tiles, 8);
    // The modifiers' time and the nodes they ran on (the estimate scales that time by nodes):
    // one tile's window is the grid; tiles' grown windows add up to more.
    EXPECT_GT(one.modifySeconds, 0.0);
    EXPECT_LE(one.modifySeconds, one.evaluateSeconds);
    const Grid& g = one.grid;
    EXPECT_EQ(one.modifiedNodes,
              double(g.cells.x + 1) * double(g.cells.y + 1) * double(g.cells.z + 1));
    EXPECT_GT(tiled.modifiedNodes, one.modifiedNodes);
    EXPECT_LT(2 * modifierHaloCells(s.root, tiled.grid.h) + 24, tiled.grid.cells.x)
        << "windows as large as the grid";
    ASSERT_GT(a.mesh.triangles.size(), 10000u);
    EXPECT_EQ(a.mesh.positions, b.mesh.positions);
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  }
  // The bundled scaffold rebuilt with an offset (of instances), in 36 tiles.
  const Scene scaffold = loadScene(assetsDir() + "/scenes/bone_scaffold.strata.json");
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  ContourReport tiled;
  const ExportMesh a = contourScene(scaffold, evaluator, ContourOptions{128, 0}, progress);
  const ExportMesh b = contourScene(scaffold, evaluator, ContourOptions{128, 32}, progress, &tiled);
  EXPECT_GT(tiled.tiles, 8);
  ASSERT_GT(a.mesh.triangles.size(), 10000u);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
}

}  // namespace
}  // namespace strata::test
