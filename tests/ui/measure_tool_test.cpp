// The measure tool's document actions (ui/measure_tool.h), without a window: two clicks make a
// distance (one undo step), a third the angle at the second point (one more), Esc closes the
// open measurement and then leaves the tool, an undo closes it too; clicks snap to a turned
// box's own corners and edge midpoints within kMeasureSnapPixels and otherwise keep the point.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "engine/document/commands.h"
#include "ui/camera.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"
#include "ui/measure_tool.h"

namespace strata::ui {
namespace {

TEST(MeasureTool, TwoClicksADistanceAThirdTheAngleEscEnds) {
  EditorState state;
  const NodeId block = addPrimitive(state, NodeKind::Box);
  setMeasuring(state, true);
  measureClick(state, block, {0, 0, 0});
  EXPECT_TRUE(state.document.scene().measurements.empty());  // one point: nothing yet
  measureClick(state, block, {3, 0, 0});
  ASSERT_EQ(state.document.scene().measurements.size(), 1u);
  EXPECT_EQ(state.document.undoLabel(), "measure");
  measureClick(state, block, {3, 4, 0});
  ASSERT_EQ(state.document.scene().measurements[0].points.size(), 3u);
  MeasureValues v = measureValues(state.document.root(), state.document.scene().measurements[0]);
  EXPECT_NEAR(v.distance, 3.0, 1e-12);
  EXPECT_NEAR(v.angleDegrees, 90.0, 1e-12);
  // The next two clicks start a new distance; Esc closes it, so a third click starts another.
  measureClick(state, 0, {10, 0, 0});
  measureClick(state, 0, {10, 0, 5});
  measureEscape(state);
  EXPECT_TRUE(state.measure.active);
  measureClick(state, 0, {20, 0, 0});
  EXPECT_EQ(state.document.scene().measurements.size(), 2u);
  EXPECT_EQ(state.document.scene().measurements[1].points.size(), 2u);
  measureEscape(state);  // drops the pending point
  EXPECT_FALSE(state.measure.first.has_value());
  measureEscape(state);  // leaves the tool
  EXPECT_FALSE(state.measure.active);
  // An undo closes the open measurement: the next click is a first point again.
  setMeasuring(state, true);
  measureClick(state, 0, {0, 9, 0});
  measureClick(state, 0, {1, 9, 0});
  undo(state);
  measureClick(state, 0, {2, 9, 0});
  EXPECT_EQ(state.document.scene().measurements.size(), 2u);
  // The first point's part deleted before the second click: measured from where it was.
  measureEscape(state);
  const NodeId doomed = addPrimitive(state, NodeKind::Sphere);
  measureClick(state, doomed, {5, 5, 5});
  state.selection = {doomed};
  deleteSelection(state);
  measureClick(state, 0, {5, 5, 9});
  const auto& list = state.document.scene().measurements;
  EXPECT_NEAR(measureValues(state.document.root(), list.back()).distance, 4.0, 1e-12);
  undo(state);
  undo(state);
  // Removing one, clearing all: one undo step each.
  removeMeasurement(state, 0);
  EXPECT_EQ(state.document.scene().measurements.size(), 1u);
  clearMeasurements(state);
  EXPECT_TRUE(state.document.scene().measurements.empty());
  undo(state);
  undo(state);
  EXPECT_EQ(state.document.scene().measurements.size(), 2u);
}

TEST(MeasureTool, ClicksSnapToATurnedBoxsCornersAndEdgeMidpoints) {
  EditorState state;
  const NodeId block = addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams p;
    p.size = glm::dvec3(4.0, 2.0, 2.0);
    state.document.setParams(block, p);
    Transform t;
    t.rotateDegrees = glm::dvec3(0.0, 0.0, 30.0);
    state.document.setTransform(block, t);
  }));
  Camera camera;
  camera.target = glm::dvec3(0.0);
  camera.distance = 20.0;
  ScreenMapping view;
  view.size = glm::dvec2(800.0, 600.0);
  view.viewProjection = camera.projection(800.0 / 600.0, 10.0) * camera.view();
  view.eye = camera.eye();
  view.forward = camera.forward();
  auto pixelOf = [&](glm::dvec3 p) {
    glm::dvec2 px;
    EXPECT_TRUE(view.toScreen(p, &px));
    return px;
  };
  const glm::dmat4 world = nodeWorldMatrix(state.document.root(), block);
  const glm::dvec3 corner = glm::dvec3(world * glm::dvec4(2.0, 1.0, 1.0, 1.0));
  const glm::dvec3 edgeMid = glm::dvec3(world * glm::dvec4(0.0, 1.0, 1.0, 1.0));
  PickHit hit;
  hit.leaf = block;
  std::string what;
  // A hit a few pixels from the corner snaps to it; so does one near an edge's midpoint.
  hit.position = corner + glm::dvec3(0.02, -0.03, 0.0);
  glm::dvec3 p = snapMeasurePoint(state, view, hit, pixelOf(corner) + glm::dvec2(4, -3), {}, &what);
  EXPECT_NEAR(glm::length(p - corner), 0.0, 1e-12);
  EXPECT_EQ(what, "corner");
  hit.position = edgeMid + glm::dvec3(0.01, 0.0, 0.0);
  p = snapMeasurePoint(state, view, hit, pixelOf(edgeMid) + glm::dvec2(2, 2), {}, &what);
  EXPECT_NEAR(glm::length(p - edgeMid), 0.0, 1e-12);
  EXPECT_EQ(what, "edge midpoint");
  // Two corners on one line of sight (looking straight down on the box): the one in front.
  Camera above;
  above.distance = 60.0;
  above.pitchDegrees = 90.0;
  ScreenMapping top = view;
  top.viewProjection = above.projection(800.0 / 600.0, 10.0) * above.view();
  const glm::dvec3 upper = glm::dvec3(world * glm::dvec4(2.0, 1.0, 1.0, 1.0));
  const glm::dvec3 lower = glm::dvec3(world * glm::dvec4(2.0, 1.0, -1.0, 1.0));
  glm::dvec2 upperPixel, lowerPixel;
  ASSERT_TRUE(top.toScreen(upper, &upperPixel) && top.toScreen(lower, &lowerPixel));
  ASSERT_LT(glm::length(upperPixel - lowerPixel), kMeasureSnapPixels);
  hit.position = upper + glm::dvec3(0.0, 0.0, -0.01);
  p = snapMeasurePoint(state, top, hit, lowerPixel, {},
                       &what);  // the lower one is nearer on screen
  EXPECT_NEAR(glm::length(p - upper), 0.0, 1e-12);
  // Far from every corner and midpoint: the surface point itself.
  const glm::dvec3 face = glm::dvec3(world * glm::dvec4(1.0, 0.3, 1.0, 1.0));
  hit.position = face;
  p = snapMeasurePoint(state, view, hit, pixelOf(face), {}, &what);
  EXPECT_EQ(p, face);
  EXPECT_EQ(what, "surface");
  hit.cap = true;
  snapMeasurePoint(state, view, hit, pixelOf(face), {}, &what);
  EXPECT_EQ(what, "section cap");
  hit.cap = false;
  // A corner the view does not show there (a cutter's corner in the air above the part, a
  // cylinder's box corner beside it) is not taken: the next one that is, or the surface point.
  hit.position = corner + glm::dvec3(0.02, -0.03, 0.0);
  const auto notTheCorner = [&](const glm::dvec3& q) { return glm::length(q - corner) > 1e-9; };
  p = snapMeasurePoint(state, view, hit, pixelOf(corner) + glm::dvec2(4, -3), notTheCorner, &what);
  EXPECT_GT(glm::length(p - corner), 1e-3);
  EXPECT_NE(what, "corner");
  p = snapMeasurePoint(
      state, view, hit, pixelOf(corner) + glm::dvec2(4, -3),
      [](const glm::dvec3&) { return false; }, &what);
  EXPECT_EQ(p, hit.position);
  EXPECT_EQ(what, "surface");
}

// On a section's cap a click snaps to the cap's nearest drawn side (PickWindow::capEdgeNear):
// a wall 10 pixels wide (1 unit a pixel, the plane z = 0) measures 10 between clicks near its
// two sides; with no side within reach, nothing.
TEST(MeasureTool, ClicksOnASectionCapSnapToItsEdges) {
  ViewportRenderer::PickWindow w;
  w.x0 = 0;
  w.y0 = 30;
  w.width = 60;
  w.height = 40;
  w.frameWidth = w.frameHeight = 100;
  // NDC (x, y, z) to world (50 x, 50 y, z): pixel x's centre at x + 0.5 - 50.
  w.toWorld = glm::dmat4(1.0);
  w.toWorld[0][0] = w.toWorld[1][1] = 50.0;
  w.sectionNormal = glm::dvec3(0, 0, 1);
  w.sectionOffset = 0.0;
  w.ids.assign(size_t(w.width * w.height), 0u);
  w.depths.assign(w.ids.size(), 0.5f);
  for (int y = w.y0; y < w.y0 + w.height; ++y)
    for (int x = 0; x < w.width; ++x)
      w.ids[w.index(x, y)] = x >= 20 && x < 30 ? 0x80000003u : x >= 45 ? 3u : 0u;
  const auto left = w.capEdgeNear(23, 50, 10.0), right = w.capEdgeNear(27, 50, 10.0);
  ASSERT_TRUE(left && right);
  EXPECT_NEAR(left->x, -30.0, 1e-9);
  EXPECT_NEAR(right->x, -20.0, 1e-9);
  EXPECT_NEAR(left->z, 0.0, 1e-9);
  EXPECT_NEAR(glm::length(*right - *left), 10.0, 1e-9);
  EXPECT_FALSE(w.capEdgeNear(5, 50, 10.0));   // 15 pixels from the cap
  EXPECT_TRUE(w.capEdgeNear(10, 50, 10.0));   // its side 10 pixels away
  EXPECT_FALSE(w.capEdgeNear(48, 50, 10.0));  // a surface, not a cap: no side of a cap near
}

// A label over the gizmo's box moves to the nearest place off it, down first, up where down
// would leave the view; one clear of it stays; one past the view's edge comes into it.
TEST(MeasureLabel, ALabelMovesOffTheGizmoAndStaysInTheView) {
  const glm::dvec2 viewLo(0, 0), viewHi(800, 600);
  const ScreenBox gizmo{{350, 250}, {450, 350}};
  const ScreenBox label{{360, 300}, {460, 330}};  // 7 steps down clear it, 10 up
  const ScreenBox moved = placedLabelBox(label, {gizmo}, viewLo, viewHi, 8.0);
  EXPECT_FALSE(moved.overlaps(gizmo));
  EXPECT_EQ(moved.lo.x, label.lo.x);
  EXPECT_GE(moved.lo.y, gizmo.hi.y);
  EXPECT_LT(moved.lo.y, gizmo.hi.y + 8.0);  // the nearest step below it
  // Near the view's foot: above the gizmo instead.
  const ScreenBox low{{350, 480}, {450, 580}};
  const ScreenBox up = placedLabelBox({{360, 540}, {460, 570}}, {low}, viewLo, viewHi, 8.0);
  EXPECT_FALSE(up.overlaps(low));
  EXPECT_LE(up.hi.y, low.lo.y);
  EXPECT_GE(up.lo.y, viewLo.y);
  // Clear of it: where it was.
  const ScreenBox clear{{10, 10}, {110, 40}};
  const ScreenBox kept = placedLabelBox(clear, {gizmo}, viewLo, viewHi, 8.0);
  EXPECT_EQ(kept.lo, clear.lo);
  // Past the right edge: moved in whole.
  const ScreenBox in = placedLabelBox({{760, 10}, {860, 40}}, {}, viewLo, viewHi, 8.0);
  EXPECT_EQ(in.hi.x, 800.0);
  EXPECT_EQ(in.lo.x, 700.0);
}

// A label (100 x 36 pixels) on a segment longer than it sits on its middle; on a short one it
// moves beside the segment: clear of the line through it and of both ends' markers, above it.
TEST(MeasureLabel, AShortSegmentsLabelGoesBesideItsLine) {
  const glm::dvec2 half(50.0, 18.0);
  EXPECT_EQ(measureLabelCentre({100, 300}, {400, 300}, half), glm::dvec2(250, 300));
  auto clear = [&](glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 c = measureLabelCentre(a, b, half);
    const glm::dvec2 corners[4] = {c + glm::dvec2(-half.x, -half.y),
                                   c + glm::dvec2(half.x, -half.y), c + glm::dvec2(half.x, half.y),
                                   c + glm::dvec2(-half.x, half.y)};
    // Every corner of the box on the same side of the line, at least the marker's 5 pixels away.
    glm::dvec2 n = b - a;
    n = glm::length(n) > 0.5 ? glm::dvec2(n.y, -n.x) / glm::length(n) : glm::dvec2(0.0, -1.0);
    int above = 0;
    for (const glm::dvec2& p : corners) {
      const double side = glm::dot(p - a, n);
      if (std::abs(side) < 5.0) return false;
      above += side > 0.0 ? 1 : -1;
    }
    return std::abs(above) == 4 && c.y < 0.5 * (a.y + b.y) + 1e-9;
  };
  EXPECT_TRUE(clear({200, 300}, {230, 300}));  // level
  EXPECT_TRUE(clear({200, 300}, {205, 270}));  // steep
  EXPECT_TRUE(clear({200, 300}, {225, 320}));  // falling
  EXPECT_TRUE(clear({200, 300}, {200, 300}));  // end-on: one point
}

}  // namespace
}  // namespace strata::ui
