// Measurements (engine/document/measurement.h): a distance between two surfels of an evaluated
// box is its edge within a cell, an angle of a right corner is 90 degrees, points follow the
// parts they lie on (and a deleted part leaves them where they were, undo brings them back), and
// scene files keep them (world coordinates with the part, version 4, clear errors).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/document/commands.h"
#include "engine/document/document.h"
#include "engine/document/measurement.h"
#include "engine/eval/evaluator.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

// The first and last surfel of the ray of axis `axis` through the node nearest `through`, in
// world coordinates.
std::pair<glm::dvec3, glm::dvec3> raySurfels(const Ldi& ldi, int axis, glm::dvec3 through) {
  const Grid& g = ldi.grid;
  const int u = g.uAxis(axis), v = g.vAxis(axis);
  const int i = int(std::lround((through[u] - g.origin[u]) / g.h)) - g.first[u];
  const int j = int(std::lround((through[v] - g.origin[v]) / g.h)) - g.first[v];
  const AxisLdi& a = ldi.axes[axis];
  EXPECT_TRUE(a.whole);  // the ray index below counts the whole grid's rays
  const int64_t ray = i + int64_t(j) * g.raysU(axis);
  const uint32_t begin = a.offsets[size_t(ray)], end = a.offsets[size_t(ray) + 1];
  EXPECT_GE(end, begin + 2u);
  auto world = [&](float depth) { return rayPoint(g, axis, a.whole, a.window, ray, depth); };
  return {world(a.surfels[begin].depth), world(a.surfels[end - 1].depth)};
}

TEST(Measurement, TwoSurfelsOfABoxGiveItsEdgeWithinACell) {
  // A turned, moved box (3 x 2 x 1.5): the x ray through its centre enters and leaves through
  // the faces of its x side only when the box is not turned about y or z: turned about x.
  Transform t;
  t.translate = glm::dvec3(0.4, -0.3, 0.2);
  t.rotateDegrees = glm::dvec3(30.0, 0.0, 0.0);
  NodePtr part = withTransform(box(glm::dvec3(3.0, 2.0, 1.5)), t);
  Document doc(makeScene(op(NodeKind::Union, {part}), 96));
  Evaluator evaluator(std::make_shared<CpuBackend>());
  Progress progress;
  const EvalResult r = evaluator.evaluate(doc.scene(), EvalOptions{}, progress);
  const std::shared_ptr<const Ldi> ldi = evaluator.backend().download(r.root);
  const auto [a, b] = raySurfels(*ldi, 0, t.translate);
  Measurement m{{attachPoint(doc.root(), part->id, a), attachPoint(doc.root(), part->id, b)}};
  doc.applyMeasurements("measure", {m});
  const MeasureValues v = measureValues(doc.root(), doc.scene().measurements[0]);
  EXPECT_NEAR(v.distance, 3.0, r.grid.h);
  EXPECT_NEAR(v.delta.x, 3.0, r.grid.h);
  EXPECT_NEAR(v.delta.y, 0.0, 1e-9);
  EXPECT_FALSE(v.hasAngle);
}

TEST(Measurement, TheAngleOfARightCornerAndOfAStraightLine) {
  const NodePtr root = op(NodeKind::Union, {box(glm::dvec3(1.0))});
  auto world = [&](glm::dvec3 p) { return attachPoint(root, 0, p); };
  MeasureValues v =
      measureValues(root, Measurement{{world({2, 0, 0}), world({0, 0, 0}), world({0, 0.5, 0})}});
  ASSERT_TRUE(v.hasAngle);
  EXPECT_NEAR(v.angleDegrees, 90.0, 1e-12);
  EXPECT_NEAR(v.distance, 2.0, 1e-15);
  EXPECT_NEAR(v.distance2, 0.5, 1e-15);
  v = measureValues(root, Measurement{{world({1, 1, 1}), world({0, 0, 0}), world({-2, -2, -2})}});
  EXPECT_NEAR(v.angleDegrees, 180.0, 1e-9);
  v = measureValues(root, Measurement{{world({1, 0, 0}), world({0, 0, 0}), world({1, 1e-9, 0})}});
  EXPECT_NEAR(v.angleDegrees, 1e-9 * 180.0 / 3.14159265358979323846, 1e-12);  // accurate near 0
}

TEST(Measurement, PointsFollowTheirPartsAndStayWhenAPartIsDeleted) {
  NodePtr part = box(glm::dvec3(2.0), {1.0, 0.0, 0.0});
  NodePtr other = sphere(0.5, {5.0, 0.0, 0.0});
  Document doc(makeScene(op(NodeKind::Union, {op(NodeKind::Union, {part}), other}), 64));
  const NodeId group = doc.root()->children[0]->id;
  const glm::dvec3 corner(2.0, 1.0, 1.0), far(5.0, 0.5, 0.0);
  doc.applyMeasurements("measure", {Measurement{{attachPoint(doc.root(), part->id, corner),
                                                 attachPoint(doc.root(), other->id, far)}}});
  EXPECT_EQ(doc.scene().measurements[0].points[0].node, part->id);
  // The group above the part turns a quarter about z: the corner turns with it.
  Transform turn;
  turn.rotateDegrees = glm::dvec3(0.0, 0.0, 90.0);
  doc.setTransform(group, turn);
  MeasureValues v = measureValues(doc.root(), doc.scene().measurements[0]);
  EXPECT_NEAR(v.a.x, -1.0, 1e-12);
  EXPECT_NEAR(v.a.y, 2.0, 1e-12);
  EXPECT_NEAR(v.b.x, 5.0, 1e-12);  // on the other part, which did not move
  // Deleting the part pins the point where it was; undo puts the part and the link back.
  doc.remove(part->id);
  const MeasurePoint pinned = doc.scene().measurements[0].points[0];
  EXPECT_EQ(pinned.node, 0u);
  EXPECT_NEAR(pinned.local.x, -1.0, 1e-12);
  EXPECT_NEAR(pinned.local.y, 2.0, 1e-12);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.scene().measurements[0].points[0].node, part->id);
  // Measurements are one undo step; bad ones are refused.
  ASSERT_TRUE(doc.undo());  // the turn
  ASSERT_TRUE(doc.undo());  // the measurement
  EXPECT_TRUE(doc.scene().measurements.empty());
  EXPECT_THROW(doc.applyMeasurements("x", {Measurement{{attachPoint(doc.root(), 0, corner)}}}),
               Error);
  MeasurePoint ghost;
  ghost.node = 9999;
  EXPECT_THROW(doc.applyMeasurements("x", {Measurement{{ghost, ghost}}}), Error);
  MeasurePoint nowhere;
  nowhere.local = glm::dvec3(1.0, std::nan(""), 0.0);
  EXPECT_THROW(doc.applyMeasurements("x", {Measurement{{nowhere, nowhere}}}), Error);  // unsaveable
  EXPECT_TRUE(doc.scene().measurements.empty());
}

// A size typed keeps a point where it lies on the part's surface: a plate 140 long made 100
// kept its 140 mm measurement, its ends in the air (an artist's test); the corners now measure
// 100. A cylinder's rim point stays on the rim as its radius grows; undo puts them back.
TEST(Measurement, PointsStayOnTheSurfaceOfAPartWhoseSizeIsTyped) {
  NodePtr plate = box(glm::dvec3(140.0, 80.0, 8.0), {0.0, 0.0, 4.0});
  NodePtr hub = cylinder(28.0, 24.0, {0.0, 0.0, 12.0});
  Document doc(makeScene(op(NodeKind::Union, {plate, hub}), 64));
  doc.applyMeasurements("measure",
                        {Measurement{{attachPoint(doc.root(), plate->id, {-70.0, -40.0, 8.0}),
                                      attachPoint(doc.root(), plate->id, {70.0, -40.0, 8.0})}},
                         Measurement{{attachPoint(doc.root(), hub->id, {28.0, 0.0, 24.0}),
                                      attachPoint(doc.root(), plate->id, {70.0, 40.0, 0.0})}}});
  PrimitiveParams shorter = plate->params;
  shorter.size = glm::dvec3(100.0, 80.0, 8.0);
  doc.setParams(plate->id, shorter);
  MeasureValues v = measureValues(doc.root(), doc.scene().measurements[0]);
  EXPECT_NEAR(v.distance, 100.0, 1e-9);
  EXPECT_NEAR(v.a.x, -50.0, 1e-9);
  EXPECT_NEAR(v.a.z, 8.0, 1e-9);
  PrimitiveParams wider = hub->params;
  wider.radius = 40.0;
  doc.setParams(hub->id, wider);
  v = measureValues(doc.root(), doc.scene().measurements[1]);
  EXPECT_NEAR(v.a.x, 40.0, 1e-9);
  EXPECT_NEAR(v.a.z, 24.0, 1e-9);
  EXPECT_NEAR(v.b.x, 50.0, 1e-9);
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_NEAR(measureValues(doc.root(), doc.scene().measurements[0]).distance, 140.0, 1e-9);
}

TEST(Measurement, SceneFilesKeepThemInWorldCoordinates) {
  Transform t;
  t.translate = glm::dvec3(1.0, 2.0, 3.0);
  t.rotateDegrees = glm::dvec3(10.0, 20.0, 30.0);
  t.scale = glm::dvec3(2.0, 1.0, 0.5);
  NodePtr part = withTransform(box(glm::dvec3(1.0)), t);
  Scene scene = makeScene(op(NodeKind::Union, {part}), 64);
  scene.measurements = {
      Measurement{{attachPoint(scene.root, part->id, {1.2, 2.1, 3.3}),
                   attachPoint(scene.root, 0, {-4.0, 0.5, 0.25})}},
      Measurement{{attachPoint(scene.root, 0, {0, 0, 0}), attachPoint(scene.root, 0, {1, 0, 0}),
                   attachPoint(scene.root, part->id, {1.0, 2.0, 3.0})}}};
  const std::string text = sceneToJson(scene);
  EXPECT_NE(text.find("\"version\": 4"), std::string::npos);
  EXPECT_NE(text.find("\"measurements\""), std::string::npos);
  const Scene back = parseScene(text, "measured.strata.json", ".");
  ASSERT_EQ(back.measurements.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(back.measurements[i].points.size(), scene.measurements[i].points.size());
    for (size_t k = 0; k < back.measurements[i].points.size(); ++k) {
      EXPECT_EQ(back.measurements[i].points[k].node, scene.measurements[i].points[k].node);
      const glm::dvec3 p = pointInWorld(back.root, back.measurements[i].points[k]);
      const glm::dvec3 q = pointInWorld(scene.root, scene.measurements[i].points[k]);
      EXPECT_NEAR(glm::length(p - q), 0.0, 1e-12) << i << " " << k;
    }
  }
  const std::pair<const char*, const char*> bad[] = {
      {R"([{"points": [{"at": [0, 0, 0]}]}])", "/measurements/0/points"},
      {R"([{"points": [{"at": [0, 0, 0]}, {"on": 77, "at": [1, 0, 0]}]}])",
       "/measurements/0/points/1/on"},
      {R"([{"points": [{"at": [0, 0]}, {"at": [1, 0, 0]}]}])", "/measurements/0/points/0/at"},
      {R"([{"points": [{"at": [0, 0, 0]}, {"at": [1, 0, 0]}], "label": "x"}])",
       "/measurements/0/label"},
      {R"({"points": []})", "/measurements"},
  };
  for (const auto& [value, pointer] : bad) {
    const std::string file =
        std::string(
            R"({"format": "strata-scene", "version": 4, "root": {"id": 1, "type": "box"}, )") +
        R"("measurements": )" + value + "}";
    try {
      parseScene(file, "bad.strata.json", ".");
      ADD_FAILURE() << "read: " << value;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace strata::test
