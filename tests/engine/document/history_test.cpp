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

// A drag's frames are worked out from where it began: the state before its first edit, known
// while it is open; each interaction begun has a number of its own, so a drag, an undo and a
// drag again from the same state are told apart.
TEST(History, AnOpenInteractionKnowsWhereItBegan) {
  History h;
  EXPECT_EQ(h.interactionStart(), nullptr);
  h.beginInteraction();
  const uint64_t first = h.interactionsBegun();
  EXPECT_EQ(h.interactionStart(), nullptr);  // nothing edited yet
  h.record(state(4), "drag");
  h.record(state(5), "drag");
  ASSERT_NE(h.interactionStart(), nullptr);
  EXPECT_EQ(h.interactionStart()->revision, 4u);
  h.beginInteraction();  // nested: the same interaction
  EXPECT_EQ(h.interactionsBegun(), first);
  h.endInteraction();
  EXPECT_EQ(h.interactionStart()->revision, 4u);
  h.endInteraction();
  EXPECT_EQ(h.interactionStart(), nullptr);
  h.beginInteraction();
  EXPECT_EQ(h.interactionsBegun(), first + 1);
  h.endInteraction();
  History other;  // another document's: its drags have numbers of their own
  other.beginInteraction();
  EXPECT_GT(other.interactionsBegun(), first + 1);
  other.endInteraction();
  History none(0);  // no steps kept: nothing to begin from
  none.beginInteraction();
  none.record(state(1), "drag");
  EXPECT_EQ(none.interactionStart(), nullptr);
}

TEST(History, KeepsAtMostTheLimit) {
  History h(3);
  for (uint64_t i = 0; i < 10; ++i) h.record(state(i), "step");
  EXPECT_EQ(h.undoSteps(), 3u);
  EXPECT_EQ(h.undo(state(10)).revision, 9u);
}

// A cancelled interaction (a drag cancelled with Escape) leaves the history as it was: the redo
// steps its first edit dropped come back (they were lost: an artist's test), and so does the
// oldest step that edit pushed out at the limit. An interaction that ends keeps its step and
// drops the redo steps, as any edit does.
TEST(History, ACancelledInteractionLeavesTheHistoryAsItWas) {
  History h(3);
  h.record(state(0), "a");
  h.record(state(1), "b");
  h.record(state(2), "c");
  EXPECT_EQ(h.undo(state(3)).revision, 2u);  // redo holds "c"
  ASSERT_TRUE(h.canRedo());
  h.beginInteraction();
  h.record(state(2), "drag");
  h.record(state(4), "drag");
  EXPECT_FALSE(h.canRedo());
  ASSERT_TRUE(h.cancelInteraction());
  EXPECT_EQ(h.redoLabel(), "c");
  EXPECT_EQ(h.undoSteps(), 2u);
  // At the limit: the oldest step comes back too.
  h.redo(state(2));
  EXPECT_EQ(h.undoSteps(), 3u);
  h.beginInteraction();
  h.record(state(3), "drag");
  EXPECT_EQ(h.undoSteps(), 3u);  // "a" pushed out
  ASSERT_TRUE(h.cancelInteraction());
  EXPECT_EQ(h.undoSteps(), 3u);
  EXPECT_EQ(h.undo(state(3)).revision, 2u);
  EXPECT_EQ(h.undo(state(2)).revision, 1u);
  EXPECT_EQ(h.undo(state(1)).revision, 0u);
  // Ended, not cancelled: the redo steps go.
  h.beginInteraction();
  h.record(state(0), "drag");
  h.endInteraction();
  EXPECT_FALSE(h.canRedo());
  EXPECT_FALSE(h.cancelInteraction());
}

}  // namespace
}  // namespace strata
