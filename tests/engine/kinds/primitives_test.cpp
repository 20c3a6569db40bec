// The primitive table: every entry, present and future, must tessellate into a closed, oriented
// mesh inside its bounds, validate its defaults, and round-trip through scene files. The rounded
// box is checked against its analytic volume and area.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

#include "engine/document/commands.h"
#include "engine/io/scene_file.h"
#include "engine/kinds/node_kinds.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {
constexpr double kPi = 3.14159265358979323846;

TEST(PrimitiveTable, EveryEntryTessellatesClosedInsideItsBounds) {
  ASSERT_GE(primitiveTable().size(), 7u);
  for (const PrimitiveInfo& info : primitiveTable()) {
    SCOPED_TRACE(info.name);
    EXPECT_NO_THROW(validatePrimitiveParams(info.kind, info.defaults));
    EXPECT_TRUE(isPrimitive(info.kind));
    EXPECT_EQ(nodeKindInfo(info.kind).primitive, &info);
    for (int segments : {3, 12, 64}) {
      TriangleMesh mesh = tessellatePrimitive(info.kind, info.defaults, segments);
      EXPECT_TRUE(test::isWatertight(mesh)) << segments << " segments";
      EXPECT_EQ(checkMesh(mesh).genus, info.kind == NodeKind::Torus ? 1 : 0);
      Bounds bounds = primitiveLocalBounds(info.kind, info.defaults);
      for (const glm::dvec3& p : mesh.positions)
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(p[a], bounds.min[a] - 1e-12);
          EXPECT_LE(p[a], bounds.max[a] + 1e-12);
        }
    }
  }
}

// A part's world bounds come from its hull, not from its local box turned (a sphere turned 45
// degrees had a box 41% too wide): every vertex of its tessellation lies within them under any
// placement (turned, mirrored, stretched, sheared), and some vertex comes near each face of
// them (tight: within the tessellation's chord error).
TEST(PrimitiveTable, WorldBoundsHoldTheTessellationUnderAnyPlacement) {
  std::vector<glm::dmat4> placements;
  for (int k = 0; k < 12; ++k) {
    const double a = 0.37 * k + 0.1, b = 0.91 * k + 0.2, c = 1.3 * k;
    glm::dmat4 m(1.0);
    m = glm::translate(m, glm::dvec3(k, -2.0 * k, 0.5));
    m = glm::rotate(m, a, glm::normalize(glm::dvec3(1.0, b, c + 0.3)));
    m = glm::scale(m, glm::dvec3(k % 3 == 0 ? -1.0 : 1.0 + 0.1 * k, 0.5 + 0.2 * k, 1.0));
    if (k % 4 == 1) m[1][0] += 0.4;  // a shear
    placements.push_back(m);
  }
  PrimitiveParams odd;  // unequal sizes and radii, each primitive's relations kept
  odd.size = glm::dvec3(3.0, 1.5, 0.8);
  odd.radius = 0.3;
  odd.topRadius = 0.1;
  odd.height = 2.5;
  odd.majorRadius = 1.2;
  odd.minorRadius = 0.35;
  for (const PrimitiveInfo& info : primitiveTable()) {
    SCOPED_TRACE(info.name);
    for (const PrimitiveParams& params : {info.defaults, odd}) {
      const TriangleMesh mesh = tessellatePrimitive(info.kind, params, 256);
      for (const glm::dmat4& m : placements) {
        const Bounds bounds = primitiveWorldBounds(info.kind, params, m);
        Bounds seen;
        for (const glm::dvec3& p : mesh.positions) seen.include(glm::dvec3(m * glm::dvec4(p, 1.0)));
        const double size = glm::length(bounds.size());
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(seen.min[a], bounds.min[a] - 1e-12 * size);
          EXPECT_LE(seen.max[a], bounds.max[a] + 1e-12 * size);
          EXPECT_LE(seen.min[a] - bounds.min[a], 1e-3 * size) << "axis " << a;
          EXPECT_LE(bounds.max[a] - seen.max[a], 1e-3 * size) << "axis " << a;
        }
      }
    }
  }
}

TEST(PrimitiveTable, EveryEntryRoundTripsThroughSceneFiles) {
  for (const PrimitiveInfo& info : primitiveTable()) {
    SCOPED_TRACE(info.name);
    NodePtr leaf = makePrimitiveNode(info.kind, 2);
    auto node = std::make_shared<Node>(*leaf);
    node->params = scaledPrimitiveParams(info.kind, info.defaults, 1.75);
    node->params.segments = 40;
    Scene scene = test::makeScene(makeOperationNode(NodeKind::Union, 1, {node}), 32);
    Scene back = parseScene(sceneToJson(scene), "t.strata.json", ".");
    NodePtr read = findNode(back.root, node->id);
    ASSERT_TRUE(read);
    EXPECT_EQ(read->kind, info.kind);
    EXPECT_EQ(read->params, node->params);
  }
}

TEST(PrimitiveTable, ParametersOutOfRangeAreRefusedWithTheirLabel) {
  for (const PrimitiveInfo& info : primitiveTable()) {
    for (const PrimitiveParam& param : info.params) {
      SCOPED_TRACE(std::string(info.name) + " " + param.key);
      PrimitiveParams p = info.defaults;
      if (param.scalar) p.*param.scalar = -1.0;
      if (param.vector) (p.*param.vector).y = -1.0;
      try {
        validatePrimitiveParams(info.kind, p);
        ADD_FAILURE() << "accepted a negative " << param.key;
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(param.label), std::string::npos) << e.what();
      }
    }
  }
}

TEST(RoundedBox, MeshMatchesTheAnalyticVolumeAndArea) {
  PrimitiveParams p;
  p.size = {2.0, 1.5, 1.0};
  p.radius = 0.2;
  const glm::dvec3 in = p.size - 2.0 * p.radius;
  const double r = p.radius;
  const double volume = in.x * in.y * in.z + 2 * r * (in.x * in.y + in.y * in.z + in.z * in.x) +
                        kPi * r * r * (in.x + in.y + in.z) + 4.0 / 3.0 * kPi * r * r * r;
  const double area = 2 * (in.x * in.y + in.y * in.z + in.z * in.x) +
                      2 * kPi * r * (in.x + in.y + in.z) + 4 * kPi * r * r;
  TriangleMesh mesh = tessellatePrimitive(NodeKind::RoundedBox, p, 256);
  MeshCheck c = checkMesh(mesh);
  EXPECT_TRUE(test::isWatertight(mesh));
  EXPECT_EQ(c.genus, 0);
  EXPECT_EQ(c.components, 1);
  EXPECT_NEAR(c.volume, volume, 1e-3 * volume);
  EXPECT_NEAR(c.area, area, 1e-3 * area);
}

TEST(RoundedBox, EvaluatesToItsVolumeAndRefusesATooLargeRadius) {
  auto node = std::make_shared<Node>(*makePrimitiveNode(NodeKind::RoundedBox, 2));
  node->params.size = {2.0, 2.0, 2.0};
  node->params.radius = 0.5;
  const double v = 1.0 + 2 * 0.5 * 3.0 + kPi * 0.25 * 3.0 + 4.0 / 3.0 * kPi * 0.125;
  EvalResult r = test::evaluateCpu(test::makeScene(test::op(NodeKind::Union, {node}), 128));
  EXPECT_NEAR(r.measure.volume, v, 0.01 * v);

  node->params.radius = 1.0;  // the inner box would vanish
  EXPECT_THROW(validatePrimitiveParams(NodeKind::RoundedBox, node->params), Error);
  const std::string file =
      R"({"format": "strata-scene", "version": 1, "root": {"id": 1, "type": "roundedBox",
      "size": [1, 1, 1], "radius": 0.5}})";
  try {
    parseScene(file, "r.strata.json", ".");
    ADD_FAILURE() << "accepted a radius of half the size";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "/root/radius: radius (0.5) must be less than 0.5, half the smallest size (1)"),
              std::string::npos)
        << e.what();
  }
}

// An artist's countersink is a cone standing on its tip: either end may be pointed (the bottom
// was refused: "radius must be greater than 0"), not both.
TEST(Cone, EitherEndMayBePointedNotBoth) {
  PrimitiveParams p;
  p.radius = 0.0;
  p.topRadius = 0.5;
  p.height = 1.0;
  validatePrimitiveParams(NodeKind::Cone, p);
  const TriangleMesh mesh = tessellatePrimitive(NodeKind::Cone, p, 256);
  EXPECT_TRUE(test::isWatertight(mesh));
  const MeshCheck c = checkMesh(mesh);
  EXPECT_NEAR(c.volume, kPi * 0.25 / 3.0, 1e-3);
  double bottomWidth = 0.0;  // the pointed end at the bottom, the wide one on top
  for (const glm::dvec3& v : mesh.positions)
    if (v.z < -0.4) bottomWidth = std::max(bottomWidth, std::hypot(v.x, v.y));
  EXPECT_LT(bottomWidth, 0.11);
  p.topRadius = 0.0;
  try {
    validatePrimitiveParams(NodeKind::Cone, p);
    ADD_FAILURE() << "a cone with no size at either end";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("both 0"), std::string::npos) << e.what();
  }
}

TEST(NodeKinds, LabelsAreForPeople) {
  EXPECT_STREQ(kindLabel(NodeKind::RoundedBox), "rounded box");
  EXPECT_STREQ(kindName(NodeKind::RoundedBox), "roundedBox");
  EXPECT_STREQ(kindLabel(NodeKind::Union), "union");
  for (const NodeKindInfo& info : nodeKindTable()) EXPECT_STRNE(kindLabel(info.kind), "");
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// A change that breaks a relation has the relation's other parameters fitted, to the 4 digits a
// field shows and strictly within it: a rounded box made 4 thick with corners of 3.5 gets 1.999;
// a torus's major radius made 2 under a minor radius of 3 gets a minor radius of 1.999. The
// parameter changed is never touched; a change of the other one, or a cone with both radii 0,
// has no fit and stays refused.
TEST(FitPrimitiveRelations, TheOtherParameterOfABrokenRelationIsMadeToFit) {
  PrimitiveParams box;
  box.size = glm::dvec3(140.0, 80.0, 4.0);
  box.radius = 3.5;
  std::vector<FittedParam> fitted = fitPrimitiveRelations(NodeKind::RoundedBox, &box, "size");
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_STREQ(fitted[0].label, "corner radius");
  EXPECT_EQ(box.radius, 1.999);
  EXPECT_EQ(fitted[0].value, 1.999);
  EXPECT_EQ(box.size.z, 4.0);
  EXPECT_NO_THROW(validatePrimitiveParams(NodeKind::RoundedBox, box));
  box.size.z = 0.0123;  // any scale: 4 digits below half
  fitPrimitiveRelations(NodeKind::RoundedBox, &box, "size");
  EXPECT_EQ(box.radius, 0.006149);
  EXPECT_NO_THROW(validatePrimitiveParams(NodeKind::RoundedBox, box));
  box.size.z = 20.0;  // a power of ten for the bound: 9.999, four digits still
  box.radius = 12.0;
  fitPrimitiveRelations(NodeKind::RoundedBox, &box, "size");
  EXPECT_EQ(box.radius, 9.999);
  box.radius = 3.5;
  box.size.z = 8.0;  // holds: nothing changed
  EXPECT_TRUE(fitPrimitiveRelations(NodeKind::RoundedBox, &box, "size").empty());
  box.radius = 5.0;  // the radius typed too large: refused, not the box shrunk
  EXPECT_TRUE(fitPrimitiveRelations(NodeKind::RoundedBox, &box, "radius").empty());
  EXPECT_EQ(box.size.z, 8.0);
  EXPECT_THROW(validatePrimitiveParams(NodeKind::RoundedBox, box), Error);

  PrimitiveParams torus;
  torus.majorRadius = 2.0;
  torus.minorRadius = 3.0;
  fitted = fitPrimitiveRelations(NodeKind::Torus, &torus, "majorRadius");
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_EQ(torus.minorRadius, 1.999);
  EXPECT_EQ(torus.majorRadius, 2.0);
  torus.minorRadius = 3.0;
  EXPECT_TRUE(fitPrimitiveRelations(NodeKind::Torus, &torus, "minorRadius").empty());

  PrimitiveParams cone;
  cone.radius = 0.0;
  cone.topRadius = 0.0;
  EXPECT_TRUE(fitPrimitiveRelations(NodeKind::Cone, &cone, "radius").empty());
}

}  // namespace
}  // namespace strata
