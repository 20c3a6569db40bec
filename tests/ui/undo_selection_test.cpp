// Undo and redo select what was selected in the state they return to (ui/editor_actions.h:
// rememberSelection), without a window.
#include <gtest/gtest.h>

#include <vector>

#include "ui/editor_actions.h"

namespace strata::ui {
namespace {

// Grouping two parts as an array and undoing it selects the two parts again (an artist's
// report: nothing was selected), and redo selects the array again.
TEST(UndoSelection, UndoingAGroupSelectsItsPartsAndRedoTheGroup) {
  EditorState state;
  const NodeId a = addPrimitive(state, NodeKind::Box);
  const NodeId b = addPrimitive(state, NodeKind::Sphere);
  state.selection = {a, b};
  rememberSelection(state);  // a frame drawn with both selected
  groupSelection(state, NodeKind::Array);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId group = state.selection[0];
  EXPECT_NE(group, a);
  EXPECT_NE(group, b);
  rememberSelection(state);

  undo(state);
  EXPECT_EQ(state.selection, (std::vector<NodeId>{a, b}));
  redo(state);
  EXPECT_EQ(state.selection, (std::vector<NodeId>{group}));
}

// A selection remembered at a state whose parts are gone later keeps only the parts still there.
TEST(UndoSelection, PartsNoLongerThereAreLeftOut) {
  EditorState state;
  const NodeId a = addPrimitive(state, NodeKind::Box);
  state.selection = {a};
  rememberSelection(state);
  const NodeId b = addPrimitive(state, NodeKind::Sphere);  // selects b
  state.selection = {a, b};
  rememberSelection(state);
  undo(state);  // b is gone; a was selected then
  EXPECT_EQ(state.selection, (std::vector<NodeId>{a}));
}

}  // namespace
}  // namespace strata::ui
