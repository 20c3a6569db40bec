// The panel sizes set by the splitters: remembered in a file between runs, and kept within the
// window (ui/panel_splitters.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ui/panel_splitters.h"

namespace strata::ui {
namespace {

TEST(PanelLayout, SizesRoundTripThroughTheFileAndBadLinesKeepTheDefaults) {
  const std::string dir = ::testing::TempDir() + "/strata_layout_test/config";
  std::filesystem::remove_all(dir);
  PanelLayout layout;
  layout.wanted.leftWidth = 411.0f;
  layout.wanted.previewHeight = 222.0f;
  writePanelLayout(dir + "/layout.txt", layout);  // creates the folder
  const PanelLayout back = readPanelLayout(dir + "/layout.txt", PanelLayout());
  EXPECT_EQ(back.leftWidth, 411.0f);
  EXPECT_EQ(back.previewHeight, 222.0f);
  EXPECT_EQ(back.rightWidth, PanelLayout().rightWidth);

  std::ofstream(dir + "/layout.txt") << "leftWidth -5\nrightWidth nonsense\nfuture 3\n"
                                     << "paletteHeight 1e30\n";
  const PanelLayout bad = readPanelLayout(dir + "/layout.txt", PanelLayout());
  EXPECT_EQ(bad.leftWidth, PanelLayout().leftWidth);
  EXPECT_EQ(bad.rightWidth, PanelLayout().rightWidth);
  EXPECT_EQ(bad.paletteHeight, PanelLayout().paletteHeight);
  EXPECT_EQ(readPanelLayout(dir + "/missing.txt", PanelLayout()).leftWidth,
            PanelLayout().leftWidth);
}

TEST(PanelLayout, SizesStayWithinTheWindow) {
  PanelLayout layout;
  layout.menuHeight = 20.0f;
  layout.statusHeight = 28.0f;
  layout.wanted.leftWidth = 5000.0f;
  layout.wanted.rightWidth = 10.0f;
  layout.wanted.paletteHeight = 5000.0f;
  clampLayout(layout, 1600.0f, 1000.0f);
  EXPECT_LE(layout.leftWidth, 1600.0f * 0.45f);
  EXPECT_GE(layout.rightWidth, 240.0f);
  EXPECT_LE(layout.paletteHeight, 1000.0f - 48.0f - 120.0f);
  EXPECT_GT(1600.0f - layout.leftWidth - layout.rightWidth, 100.0f);  // the view keeps room
}

// A window made small and then large again shows the panels as they were set: the sizes shown
// shrink with the window, the sizes wanted stay (and are what the file keeps).
TEST(PanelLayout, AWindowMadeSmallThenLargeShowsThePanelsAsTheyWereSet) {
  PanelLayout layout;
  layout.menuHeight = 20.0f;
  layout.statusHeight = 28.0f;
  layout.wanted.leftWidth = 380.0f;
  layout.wanted.rightWidth = 400.0f;
  clampLayout(layout, 1600.0f, 1000.0f);
  EXPECT_EQ(layout.leftWidth, 380.0f);
  EXPECT_EQ(layout.rightWidth, 400.0f);
  clampLayout(layout, 900.0f, 600.0f);
  EXPECT_LT(layout.leftWidth, 380.0f);
  EXPECT_LT(layout.rightWidth, 400.0f);
  EXPECT_GE(900.0f - layout.leftWidth - layout.rightWidth, 0.35f * 900.0f - 1.0f);  // the view
  clampLayout(layout, 500.0f, 400.0f);
  EXPECT_GE(layout.leftWidth, 200.0f);  // never below the minimums
  clampLayout(layout, 1600.0f, 1000.0f);
  EXPECT_EQ(layout.leftWidth, 380.0f);
  EXPECT_EQ(layout.rightWidth, 400.0f);
  EXPECT_EQ(layout.wanted.leftWidth, 380.0f);
}

}  // namespace
}  // namespace strata::ui
