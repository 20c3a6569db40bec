// meshWorldBounds answers through a tree of the mesh's vertices what transforming every vertex
// answers, bit for bit: the grid of every evaluation is built from these bounds, so a bound one
// ulp off would move every sample.
#include "engine/geometry/mesh_world_bounds.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

#include "tests/support/scene_builder.h"

namespace strata {
namespace {

// Through the mesh's tree (built now; without it the first bounds asked are scanned).
Bounds throughTree(const std::shared_ptr<const TriangleMesh>& mesh, const glm::dmat4& world) {
  prepareMeshWorldBounds(mesh);
  return meshWorldBounds(mesh, world);
}

void expectSameBits(const Bounds& a, const Bounds& b, const std::string& what) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.min[i], b.min[i]) << what << " min " << i;
    EXPECT_EQ(a.max[i], b.max[i]) << what << " max " << i;
  }
}

// Rotations about random axes, uneven and mirroring scales, shears and translations small and
// far: the transforms a scene's nesting multiplies together.
std::vector<glm::dmat4> transforms(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<glm::dmat4> out{glm::dmat4(1.0)};
  for (int i = 0; i < count; ++i) {
    glm::dmat4 m(1.0);
    m = glm::translate(
        m, glm::dvec3(unit(rng), unit(rng), unit(rng)) * std::pow(10.0, 6.0 * unit(rng)));
    const glm::dvec3 axis = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)) + 1e-3);
    m = glm::rotate(m, 3.2 * unit(rng), axis);
    m = glm::scale(m,
                   glm::dvec3(unit(rng), unit(rng), unit(rng)) * std::pow(10.0, 3.0 * unit(rng)));
    if (i % 3 == 0) m[1][0] += unit(rng);  // a shear
    out.push_back(m);
  }
  out.push_back(glm::rotate(glm::dmat4(1.0), glm::radians(90.0), glm::dvec3(0, 0, 1)));
  return out;
}

TEST(MeshWorldBounds, RealMeshesUnderManyTransformsMatchTheScanBitForBit) {
  for (const char* file : {"armadillo.obj", "fandisk.obj", "knot1.obj"}) {
    const auto mesh = test::dataMesh(file);
    for (const glm::dmat4& world : transforms(7, 60))
      expectSameBits(throughTree(mesh, world), transformedBounds(mesh->positions, world), file);
  }
}

// A lattice of points: whole faces of vertices tie for each extreme (a CAD part's flat sides),
// the case where a search that stopped at the first box found could pick a different double.
TEST(MeshWorldBounds, FlatSidesWhereManyVerticesTieMatchTheScan) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 20; ++y)
      for (int z = 0; z < 20; ++z) mesh->positions.push_back(glm::dvec3(x, y, z) * 0.1 + 0.3);
  for (const glm::dmat4& world : transforms(11, 40))
    expectSameBits(throughTree(mesh, world), transformedBounds(mesh->positions, world), "lattice");
}

// A mesh freed and another made at its address gets its own tree, not the dead mesh's; a mesh
// asked again and again gets its tree without being prepared.
TEST(MeshWorldBounds, AMeshMadeWhereAnotherDiedIsNotAnsweredWithTheOldTree) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int round = 0; round < 6; ++round) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 5000; ++i)
      mesh->positions.push_back(glm::dvec3(unit(rng), unit(rng), unit(rng)) * double(round + 1));
    const glm::dmat4 world = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(1, 1, 0));
    for (int asked = 0; asked < 20; ++asked)
      expectSameBits(meshWorldBounds(mesh, world), transformedBounds(mesh->positions, world),
                     "round");
  }
}

TEST(MeshWorldBounds, NonFiniteTransformsAndEmptyMeshesAreAnsweredAsTheScanDoes) {
  EXPECT_TRUE(meshWorldBounds(nullptr, glm::dmat4(1.0)).empty());
  EXPECT_TRUE(meshWorldBounds(std::make_shared<TriangleMesh>(), glm::dmat4(1.0)).empty());
  const auto mesh = test::dataMesh("armadillo.obj");
  glm::dmat4 huge(1.0);
  huge[0][0] = 1e307;
  huge[3][1] = 1e308;
  expectSameBits(throughTree(mesh, huge), transformedBounds(mesh->positions, huge), "huge");
}

}  // namespace
}  // namespace strata
