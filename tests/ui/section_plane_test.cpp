// The section plane's place (ui/viewport.h: sectionAt, placeSection), without a window.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "engine/document/node.h"
#include "ui/editor_actions.h"
#include "ui/scene_queries.h"
#include "ui/viewport.h"

namespace strata::ui {
namespace {

// Once placed, the plane stays where it is in the scene when a part moves (an artist's report:
// it was kept as a fraction of the scene's bounds, so moving a part moved the cut).
TEST(SectionPlane, StaysInTheSceneWhenAPartMoves) {
  EditorState state;
  const NodeId box = addPrimitive(state, NodeKind::Box);
  state.section.on = true;
  state.section.axis = 0;
  state.section.startFraction = 0.25;
  const Bounds before = sceneBounds(state.document.root());
  ASSERT_FALSE(before.empty());
  placeSection(state);
  ASSERT_TRUE(state.section.at.has_value());
  const double expected = before.min.x + 0.25 * (before.max.x - before.min.x);
  EXPECT_DOUBLE_EQ(*state.section.at, expected);

  Transform moved = findNode(state.document.root(), box)->transform;
  moved.translate.x += 3.0 * (before.max.x - before.min.x);
  state.document.setTransform(box, moved);
  placeSection(state);  // the next frame
  glm::dvec3 normal;
  double offset = 0.0;
  ASSERT_TRUE(sectionPlane(state, &normal, &offset));
  EXPECT_EQ(normal, glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(offset, expected);
  EXPECT_DOUBLE_EQ(sectionAt(state.section, sceneBounds(state.document.root())), expected);
}

// An unplaced plane lies at its fraction of the bounds, flipped or not; a new document places
// it again in the middle of its parts.
TEST(SectionPlane, UnplacedLiesAtItsFractionAndANewDocumentUnplacesIt) {
  EditorState state;
  addPrimitive(state, NodeKind::Sphere);
  const Bounds b = sceneBounds(state.document.root());
  state.section.on = true;
  state.section.axis = 2;
  state.section.flip = true;
  glm::dvec3 normal;
  double offset = 0.0;
  ASSERT_TRUE(sectionPlane(state, &normal, &offset));
  EXPECT_EQ(normal, glm::dvec3(0.0, 0.0, -1.0));
  EXPECT_DOUBLE_EQ(-offset, 0.5 * (b.min.z + b.max.z));
  state.section.at = 123.0;
  newDocument(state);
  EXPECT_FALSE(state.section.at.has_value());
  placeSection(state);  // an empty scene: nothing to place it in
  EXPECT_FALSE(state.section.at.has_value());
}

}  // namespace
}  // namespace strata::ui
