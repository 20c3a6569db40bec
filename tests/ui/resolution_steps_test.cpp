// The Preview panel's resolution steps (ui/panels.h: resolutionStepNearest, resolutionStepAfter).
#include <gtest/gtest.h>

#include "ui/editor_actions.h"
#include "ui/editor_state.h"
#include "ui/panels.h"

namespace strata::ui {
namespace {

TEST(ResolutionSteps, ADragLandsOnThePowersOfTwoAndTheHalvesBetween) {
  EXPECT_EQ(resolutionStepNearest(16), 16);
  EXPECT_EQ(resolutionStepNearest(117), 128);  // the artist's drag from 256
  EXPECT_EQ(resolutionStepNearest(250), 256);
  EXPECT_EQ(resolutionStepNearest(300), 256);  // log(300/256) < log(384/300)
  EXPECT_EQ(resolutionStepNearest(330), 384);
  EXPECT_EQ(resolutionStepNearest(700), 768);
  EXPECT_EQ(resolutionStepNearest(1024), 1024);
  EXPECT_EQ(resolutionStepNearest(1000), 1024);
  EXPECT_EQ(resolutionStepNearest(20), 24);  // log(24/20) < log(20/16)
  // Every step is its own nearest; the steps between 16 and 1024 are 13.
  int count = 0;
  for (int r = 16; r <= 1024; ++r)
    if (resolutionStepNearest(r) == r) ++count;
  EXPECT_EQ(count, 13);
}

TEST(ResolutionSteps, MinusAndPlusStepFromAnyResolutionWithinTheRange) {
  EXPECT_EQ(resolutionStepAfter(256, +1, 16, 1024), 384);
  EXPECT_EQ(resolutionStepAfter(256, -1, 16, 1024), 192);
  EXPECT_EQ(resolutionStepAfter(300, +1, 16, 1024), 384);  // typed, not a step
  EXPECT_EQ(resolutionStepAfter(300, -1, 16, 1024), 256);
  EXPECT_EQ(resolutionStepAfter(1024, +1, 16, 1024), 1024);  // the end: the button is disabled
  EXPECT_EQ(resolutionStepAfter(16, -1, 16, 1024), 16);
  EXPECT_EQ(resolutionStepAfter(2000, -1, 16, 2000), 1536);
}

// `strata edit --resolution N`: File > New previews the new document at N (it went back to 256
// whatever the command line said), as a document of its own (not modified, nothing to undo).
TEST(ResolutionSteps, ANewDocumentTakesTheResolutionTheEditorWasStartedWith) {
  EditorState state;
  state.newDocumentResolution = 512;
  newDocument(state);
  EXPECT_EQ(state.document.scene().settings.resolution, 512);
  EXPECT_FALSE(state.document.dirty());
  EXPECT_FALSE(state.document.canUndo());
  EXPECT_NE(state.log.back().text.find("512 cells"), std::string::npos) << state.log.back().text;
  state.newDocumentResolution = 0;
  newDocument(state);
  EXPECT_EQ(state.document.scene().settings.resolution, SceneSettings().resolution);
}

}  // namespace
}  // namespace strata::ui
