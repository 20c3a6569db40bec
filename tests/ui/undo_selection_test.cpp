// Undo and redo select what was selected in the state they return to (ui/editor_actions.h:
// rememberSelection), without a window.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/io/document_files.h"
#include "engine/io/recovery_slots.h"
#include "engine/io/user_files.h"
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

// Ctrl+Z in the middle of a gizmo drag closed the drag's undo step under it: the drag went on
// recording a step a frame until the history held nothing else (an artist's test). Now it
// cancels the drag, as Escape does; with another drag under way (an inspector field held) it
// waits. Nothing of the history is lost either way.
TEST(UndoSelection, UndoDuringADragCancelsItOrWaitsAndKeepsTheHistory) {
  EditorState state;
  const NodeId a = addPrimitive(state, NodeKind::Box);
  addPrimitive(state, NodeKind::Sphere);
  const std::string before = state.document.undoLabel();
  // A gizmo drag under way: its interaction open, one step recorded.
  state.document.beginInteraction();
  Transform moved = findNode(state.document.root(), a)->transform;
  moved.translate.x += 5.0;
  state.document.setTransform(a, moved);
  state.gizmoDragging = true;
  undo(state);
  EXPECT_TRUE(state.cancelGizmoDrag) << "the drag is cancelled (the viewport does it)";
  EXPECT_TRUE(state.document.interacting()) << "the undo left the drag's step alone";
  EXPECT_NE(state.log.back().text.find("the drag is cancelled"), std::string::npos);
  // What the viewport does with the cancel: the drag's step taken back, the history as before.
  state.document.cancelInteraction();
  state.gizmoDragging = state.cancelGizmoDrag = false;
  EXPECT_EQ(state.document.undoLabel(), before);
  // An inspector field dragged with the mouse: undo and redo cancel its drag too (they were
  // ignored, and the drag committed on release: an artist's test); its step goes back.
  state.document.beginInteraction();
  state.document.setTransform(a, moved);
  state.fieldDragHeld = true;
  redo(state);
  EXPECT_TRUE(state.cancelFieldDrag) << "the drag is cancelled (the editor lets the field go)";
  EXPECT_TRUE(state.document.interacting()) << "the redo left the drag's step alone";
  EXPECT_NE(state.log.back().text.find("the field's value is back"), std::string::npos);
  state.document.cancelInteraction();
  state.fieldDragHeld = state.cancelFieldDrag = false;
  EXPECT_EQ(state.document.undoLabel(), before);
  EXPECT_EQ(findNode(state.document.root(), a)->transform.translate.x, moved.translate.x - 5.0);
  // Another interaction under way (a palette drag held): undo and redo wait, the history
  // untouched.
  state.document.beginInteraction();
  state.document.setTransform(a, moved);
  undo(state);
  redo(state);
  EXPECT_TRUE(state.document.interacting());
  EXPECT_NE(state.log.back().text.find("waits until"), std::string::npos);
  state.document.endInteraction();
  undo(state);  // the move's step, then the two parts
  undo(state);
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), a));
}

// Ctrl+S over a file another editor wrote since it was opened here asks first (the question's
// text in state.overwriteQuestion) and writes nothing until answered.
TEST(UndoSelection, SavingOverAFileChangedOnDiskAsksFirst) {
  const std::string folder = ::testing::TempDir() + "/strata_changed_on_disk";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::string path = folder + "/part.strata.json";
  EditorState state;
  addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(saveDocumentAs(state, path));
  Document other = strata::openDocument(path);
  other.addNode(NodeKind::Sphere);
  strata::saveDocument(other);
  const auto size = std::filesystem::file_size(path);
  addPrimitive(state, NodeKind::Torus);
  EXPECT_FALSE(saveDocument(state));
  EXPECT_NE(state.overwriteQuestion.find("another editor or program"), std::string::npos);
  EXPECT_EQ(std::filesystem::file_size(path), size) << "nothing written before the answer";
  EXPECT_TRUE(state.document.dirty());
  std::filesystem::remove_all(folder);
}

// The recovery question with the work of two editors that ended without saving: the newest is
// asked about first; a Recover takes it and leaves the other for a later start (recovering it
// here would replace the first, unsaved); Discard keeps it aside; nothing is lost.
TEST(UndoSelection, RecoveringOneOfTwoLeavesTheOtherForLater) {
  const std::string dir = ::testing::TempDir() + "/strata_recover_two";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Document older, newer;
  older.addNode(NodeKind::Box);
  newer.addNode(NodeKind::Torus);
  writeRecoveryFile(older, dir + "/900001-0.strata.json");
  std::filesystem::last_write_time(
      dir + "/900001-0.strata.json",
      std::filesystem::file_time_type::clock::now() - std::chrono::minutes(5));
  writeRecoveryFile(newer, dir + "/900002-0.strata.json");
  EditorState state;
  state.recoveryDir = dir;
  state.recoveryOffers = claimOrphanedRecoveries(dir);
  state.offerRecovery = true;
  ASSERT_EQ(state.recoveryOffers.size(), 2u);
  EXPECT_TRUE(recoverDocument(state));
  ASSERT_EQ(state.document.root()->children.size(), 1u);
  EXPECT_EQ(state.document.root()->children[0]->kind, NodeKind::Torus) << "the newest first";
  EXPECT_TRUE(state.document.dirty());
  EXPECT_FALSE(state.offerRecovery) << "the other is not offered over the recovered work";
  EXPECT_FALSE(std::filesystem::exists(dir + "/900002-0.strata.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/900001-0.strata.json")) << "left for later";
  // The next start: offered, discarded, kept aside.
  state.recoveryOffers = claimOrphanedRecoveries(dir);
  state.offerRecovery = true;
  ASSERT_EQ(state.recoveryOffers.size(), 1u);
  discardRecovery(state);
  EXPECT_FALSE(state.offerRecovery);
  EXPECT_FALSE(std::filesystem::exists(dir + "/900001-0.strata.json"));
  EXPECT_NE(state.log.back().text.find("/discarded/"), std::string::npos) << state.log.back().text;
  std::filesystem::remove_all(dir);
}

// A recovery file that cannot be read (damaged JSON): Recover says why and moves it aside with
// the discarded ones; it was left in place and offered again, to fail again, at every start.
TEST(UndoSelection, ADamagedRecoveryFileIsKeptAsideAndNotOfferedAgain) {
  const std::string dir = ::testing::TempDir() + "/strata_recover_damaged";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    std::ofstream damaged(dir + "/900003-0.strata.json");
    damaged << "{\"version\": 2, \"root\": {\"kind\": \"union\", \"children\": [";
  }
  EditorState state;
  state.recoveryDir = dir;
  state.recoveryOffers = claimOrphanedRecoveries(dir);
  state.offerRecovery = true;
  ASSERT_EQ(state.recoveryOffers.size(), 1u);
  EXPECT_FALSE(recoverDocument(state));
  EXPECT_FALSE(state.offerRecovery);
  EXPECT_TRUE(state.document.root()->children.empty()) << "the document is left as it was";
  EXPECT_NE(state.log.back().text.find("/discarded/"), std::string::npos) << state.log.back().text;
  EXPECT_NE(state.log.back().text.find("line 1"), std::string::npos)
      << "the reader's reason in the same line: " << state.log.back().text;
  EXPECT_FALSE(std::filesystem::exists(dir + "/900003-0.strata.json"));
  bool kept = false;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/discarded"))
    kept = kept || e.path().filename().string().find("900003-0") != std::string::npos;
  EXPECT_TRUE(kept) << "nothing is lost";
  EXPECT_TRUE(claimOrphanedRecoveries(dir).empty()) << "not offered at the next start";
  std::filesystem::remove_all(dir);
}

// The demo opens as an untitled copy: the title names what it is a copy of (a bare
// "untitled" under the demo's parts puzzled an artist), until another document replaces it or
// it is saved under a name of its own.
TEST(WindowTitle, AnUntitledCopyNamesItsTemplate) {
  EditorState state;
  EXPECT_EQ(windowTitle(state), "Strata \u2014 untitled");
  ASSERT_TRUE(openTemplate(state, std::string(STRATA_ASSETS) + "/scenes/demo.strata.json"));
  EXPECT_EQ(windowTitle(state), "Strata \u2014 untitled (a copy of demo.strata.json)");
  addPrimitive(state, NodeKind::Box);
  EXPECT_EQ(windowTitle(state), "Strata \u2014 untitled (a copy of demo.strata.json) *");
  const std::string path = ::testing::TempDir() + "/strata_title_test.strata.json";
  ASSERT_TRUE(saveDocumentAs(state, path));
  EXPECT_EQ(windowTitle(state), "Strata \u2014 strata_title_test.strata.json");
  newDocument(state);
  EXPECT_EQ(windowTitle(state), "Strata \u2014 untitled");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace strata::ui
