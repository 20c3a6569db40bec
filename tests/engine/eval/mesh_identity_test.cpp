// Identities that need no reference, on real meshes from ../shared/data (copied to tests/data):
// V(A u B) + V(A n B) = V(A) + V(B), disjoint unions add up, and the sampled volume of a single
// mesh approaches its exact (signed-tetrahedra) volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

struct MeshCase {
  const char* file;
  double volume;  // reference volume from shared/data/README.md
};

class MeshIdentity : public ::testing::TestWithParam<MeshCase> {};

TEST_P(MeshIdentity, InclusionExclusionHoldsPerRay) {
  auto mesh = dataMesh(GetParam().file);
  Bounds b = meshBounds(*mesh);
  glm::dvec3 shift = b.size() * glm::dvec3(0.31, 0.17, -0.07);
  NodePtr a = meshLeaf(mesh);
  NodePtr c = meshLeaf(mesh, shift);
  // All four evaluations on one grid (the union's), so the identity holds ray by ray.
  Bounds all = b;
  all.include(Bounds{b.min + shift, b.max + shift});
  Scene base = makeSceneInBox(a, 96, all.min - b.size() * 0.1, all.max + b.size() * 0.1);
  double slack = 0.0;  // events merged as coincident may each move by kCoincidentDepth cells
  auto on = [&](NodePtr root) {
    Scene s = base;
    s.root = std::move(root);
    EvalResult r = evaluateCpu(s);
    double h = r.grid.h;
    slack = std::max(slack, double(r.measure.surfels) * kCoincidentDepth * h * h * h);
    return r.measure.volume;
  };
  double va = on(a), vc = on(c);
  double vu = on(op(NodeKind::Union, {a, c})), vi = on(op(NodeKind::Intersection, {a, c}));
  EXPECT_GT(vi, 0.0);
  EXPECT_NEAR(vu + vi, va + vc, 1e-12 * va + slack) << GetParam().file;
  EXPECT_NEAR(on(op(NodeKind::Difference, {a, c})), va - vi, 1e-12 * va + slack);
}

TEST_P(MeshIdentity, DisjointUnionAddsUp) {
  auto mesh = dataMesh(GetParam().file);
  Bounds b = meshBounds(*mesh);
  glm::dvec3 shift(b.size().x * 1.5, 0, 0);
  NodePtr a = meshLeaf(mesh), c = meshLeaf(mesh, shift);
  Bounds all = b;
  all.include(Bounds{b.min + shift, b.max + shift});
  Scene s = makeSceneInBox(op(NodeKind::Union, {a, c}), 160, all.min - b.size() * 0.05,
                           all.max + b.size() * 0.05);
  double vu = evaluateCpu(s).measure.volume;
  s.root = a;
  double va = evaluateCpu(s).measure.volume;
  s.root = c;
  double vc = evaluateCpu(s).measure.volume;
  EXPECT_NEAR(vu, va + vc, 1e-9 * vu);
}

TEST_P(MeshIdentity, SampledVolumeApproachesExactVolume) {
  auto mesh = dataMesh(GetParam().file);
  const double exact = GetParam().volume;
  EXPECT_NEAR(signedVolume(*mesh), exact, 1e-5 * exact);
  double area = surfaceArea(*mesh);
  for (int resolution : {64, 128}) {
    EvalResult r = evaluateCpu(makeScene(meshLeaf(mesh), resolution));
    EXPECT_NEAR(r.measure.volume, exact, 0.25 * r.grid.h * area)
        << GetParam().file << " at " << resolution;
  }
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, MeshIdentity,
                         ::testing::Values(MeshCase{"bunny.obj", 194.288371812},
                                           MeshCase{"eight.obj", 0.0401729},
                                           MeshCase{"knot1.obj", 0.0951747},
                                           MeshCase{"fandisk.obj", 0.14036}),
                         [](const auto& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('.'));
                         });

}  // namespace
}  // namespace strata::test
