// Undo/redo snapshots and the coalescing of interactions (engine/document/history.h).
#include <gtest/gtest.h>

#include "engine/document/history.h"

namespace strata {
namespace {

DocumentState state(uint64_t revision) {
  return DocumentState{std::make_shared<const Scene>(), revision};
}

TEST(History, UndoAndRedoWalkTheSteps) {
  History h;
  EXPECT_FALSE(h.canUndo());
  h.record(state(0), "first");
  h.record(state(1), "second");
  EXPECT_EQ(h.undoLabel(), "second");
  DocumentState back = h.undo(state(2));
  EXPECT_EQ(back.revision, 1u);
  EXPECT_EQ(h.redoLabel(), "second");
  DocumentState again = h.redo(back);
  EXPECT_EQ(again.revision, 2u);
  EXPECT_EQ(h.undo(again).revision, 1u);
  EXPECT_EQ(h.undo(state(1)).revision, 0u);
  EXPECT_FALSE(h.canUndo());
  EXPECT_EQ(h.redoSteps(), 2u);
  h.record(state(0), "branch");  // a new edit drops the redo steps
  EXPECT_FALSE(h.canRedo());
}

TEST(History, AnInteractionIsOneStep) {
  History h;
  h.beginInteraction();
  h.record(state(0), "drag");
  h.record(state(1), "drag");
  h.record(state(2), "drag");
  h.endInteraction();
  EXPECT_EQ(h.undoSteps(), 1u);
  EXPECT_EQ(h.undo(state(3)).revision, 0u);
  // Nested interactions close with the outermost.
  h.beginInteraction();
  h.beginInteraction();
  h.record(state(0), "a");
  h.endInteraction();
  h.record(state(1), "a");
  h.endInteraction();
  h.record(state(2), "b");
  EXPECT_EQ(h.undoSteps(), 2u);
}

TEST(History, KeepsAtMostTheLimit) {
  History h(3);
  for (uint64_t i = 0; i < 10; ++i) h.record(state(i), "step");
  EXPECT_EQ(h.undoSteps(), 3u);
  EXPECT_EQ(h.undo(state(10)).revision, 9u);
}

}  // namespace
}  // namespace strata
