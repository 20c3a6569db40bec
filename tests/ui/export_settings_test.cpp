// The export dialog's choices kept between runs (ui/export_settings.h), and an export started
// from the editor writing them.
#include "ui/export_settings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "engine/eval/cpu_backend.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"

namespace strata::ui {
namespace {

TEST(ExportSettings, RoundTripAndBadLinesKeepTheDefaults) {
  const std::string folder = ::testing::TempDir() + "/strata_export_settings";
  std::filesystem::remove_all(folder);
  const std::string path = folder + "/export.txt";
  const ExportSettings defaults;
  EXPECT_EQ(readExportSettings(path, defaults).resolution, 0);  // no file: the defaults
  writeExportSettings(path, {512, true, 0.5f});
  const ExportSettings back = readExportSettings(path, defaults);
  EXPECT_EQ(back.resolution, 512);
  EXPECT_TRUE(back.simplify);
  EXPECT_FLOAT_EQ(back.simplifyCells, 0.5f);
  {
    std::ofstream out(path);
    out << "resolution 99999999\nsimplify 7\nsimplifyCells nan\nwhat 3\nsimplifyCells 0.3\n";
  }
  const ExportSettings bad = readExportSettings(path, defaults);
  EXPECT_EQ(bad.resolution, 0);
  EXPECT_FALSE(bad.simplify);
  EXPECT_FLOAT_EQ(bad.simplifyCells, 0.3f);
  std::filesystem::remove_all(folder);
}

TEST(ExportSettings, AnExportRemembersItsChoices) {
  const std::string folder = ::testing::TempDir() + "/strata_export_settings_job";
  std::filesystem::remove_all(folder);
  EditorState state;
  state.makeBackend = [] { return std::make_shared<CpuBackend>(); };
  state.exportSettingsPath = folder + "/export.txt";
  addPrimitive(state, NodeKind::Sphere);
  startExport(state, folder + "/ball.stl", 48, 0.25, false);
  ASSERT_TRUE(state.exportJob);
  const ExportSettings kept = readExportSettings(state.exportSettingsPath, {});
  EXPECT_EQ(kept.resolution, 48);
  EXPECT_TRUE(kept.simplify);
  EXPECT_FLOAT_EQ(kept.simplifyCells, 0.25f);
  state.exportJob.reset();  // waits for it
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace strata::ui
