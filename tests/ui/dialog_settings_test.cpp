// The export dialog's choices kept between runs (ui/dialog_settings.h), and an export started
// from the editor writing them.
#include "ui/dialog_settings.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"
#include "ui/panels.h"

namespace strata::ui {
namespace {

TEST(ExportSettings, RoundTripAndBadLinesKeepTheDefaults) {
  const std::string folder = ::testing::TempDir() + "/strata_export_settings";
  std::filesystem::remove_all(folder);
  const std::string path = folder + "/export.txt";
  const ExportSettings defaults;
  EXPECT_EQ(readExportSettings(path, defaults).resolution, 0);  // no file: the defaults
  writeExportSettings(path, {512, true, 0.5f, "/tmp/a folder"});
  const ExportSettings back = readExportSettings(path, defaults);
  EXPECT_EQ(back.resolution, 512);
  EXPECT_TRUE(back.simplify);
  EXPECT_FLOAT_EQ(back.simplifyCells, 0.5f);
  EXPECT_EQ(back.folder, "/tmp/a folder");
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

// An export into a folder that takes no file does not start, and says so where the export's
// progress would show: the export window's own state, not only the status bar (an artist's
// test); the next export that starts clears it.
TEST(ExportSettings, AnExportThatCannotStartSaysWhyInItsWindow) {
  const std::string folder = ::testing::TempDir() + "/strata_export_not_started";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  EditorState state;
  state.makeBackend = [] { return std::make_shared<CpuBackend>(); };
  addPrimitive(state, NodeKind::Sphere);
  startExport(state, "/proc/ball.stl", 32, 0.0, false);
  EXPECT_FALSE(state.exportJob);
  ASSERT_TRUE(state.exportNotStarted);
  EXPECT_EQ(state.exportNotStarted->path, "/proc/ball.stl");
  EXPECT_NE(state.exportNotStarted->why.find("cannot create a file in /proc"), std::string::npos)
      << state.exportNotStarted->why;
  ASSERT_FALSE(state.log.empty());
  EXPECT_NE(state.log.back().text.find("/proc/ball.stl"), std::string::npos);
  startExport(state, folder + "/ball.stl", 32, 0.0, false);
  EXPECT_TRUE(state.exportJob);
  EXPECT_FALSE(state.exportNotStarted);
  // Refused after that one ended, the window shows the refusal alone (both were drawn into the
  // one "Export" window).
  for (int waited = 0; !state.exportJob->status().finished && waited < 120000; waited += 5)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  startExport(state, "/proc/ball.stl", 32, 0.0, false);
  EXPECT_FALSE(state.exportJob);
  EXPECT_TRUE(state.exportNotStarted);
  startExport(state, folder + "/ball.stl", 32, 0.0, false);
  state.exportJob.reset();  // cancels and joins
  std::filesystem::remove_all(folder);
}

TEST(ExportSettings, AnExportRemembersItsChoices) {
  const std::string folder = ::testing::TempDir() + "/strata_export_settings_job";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);  // an export's folder must exist (cannotWriteAt)
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
  EXPECT_EQ(std::filesystem::path(kept.folder),
            std::filesystem::absolute(folder).lexically_normal());
  // Its end said in the log, once (the status bar kept "exporting ..." after it: an artist).
  for (int waited = 0; !state.exportJob->status().finished && waited < 120000; waited += 5)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(state.exportJob->status().finished);
  logExportEnd(state);
  EXPECT_NE(state.log.back().text.find("exported " + folder + "/ball.stl: written and checked"),
            std::string::npos)
      << state.log.back().text;
  const size_t lines = state.log.size();
  logExportEnd(state);
  EXPECT_EQ(state.log.size(), lines);
  state.exportJob.reset();
  std::filesystem::remove_all(folder);
}

// The export dialog's choices were made for the document they exported: a new or opened one
// starts from its own resolution, unsimplified (after Ctrl+O a quick Export wrote a coarser,
// simplified mesh than the scene asked for: an artist's test); the tolerance, a preference,
// stays. The palette's mode goes back to adding too.
TEST(ExportSettings, AnotherDocumentStartsFromItsOwnResolution) {
  EditorState state;
  state.exportResolution = 128;
  state.exportSimplify = true;
  state.exportSimplifyCells = 0.5f;
  state.placeMode = PlaceMode::Cut;
  newDocument(state);
  EXPECT_EQ(state.placeMode, PlaceMode::Add) << "the palette adds again";
  EXPECT_EQ(state.exportResolution, 0) << "the dialog takes the scene's";
  EXPECT_FALSE(state.exportSimplify);
  EXPECT_FLOAT_EQ(state.exportSimplifyCells, 0.5f);
}

// An artist's Ctrl+Q at "evaluate 10%" closed the editor and the export with it, without a word:
// quitting while an export runs asks first; once it has ended, quitting goes on as before (here
// to the unsaved-changes question, the document being new).
TEST(ExportSettings, QuittingWhileAnExportRunsAsksFirst) {
  const std::string folder = ::testing::TempDir() + "/strata_export_quit";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  EditorState state;
  state.makeBackend = [] { return std::make_shared<CpuBackend>(); };
  addPrimitive(state, NodeKind::Sphere);
  startExport(state, folder + "/ball.stl", 1024, 0.0, true);
  ASSERT_TRUE(state.exportJob);
  ASSERT_TRUE(state.exportJob->status().running);
  requestQuit(state);
  EXPECT_TRUE(state.askingQuitDuringExport);
  EXPECT_FALSE(state.quitNow);
  EXPECT_FALSE(state.pendingReplace);
  state.exportJob->cancel();
  for (int waited = 0; !state.exportJob->status().finished && waited < 120000; waited += 5)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(state.exportJob->status().finished);
  logExportEnd(state);
  EXPECT_NE(state.log.back().text.find("cancelled; nothing was written"), std::string::npos)
      << state.log.back().text;
  state.exportJob.reset();
  state.askingQuitDuringExport = false;
  requestQuit(state);
  EXPECT_FALSE(state.askingQuitDuringExport);
  ASSERT_TRUE(state.pendingReplace);
  EXPECT_EQ(state.pendingReplace->kind, PendingReplace::Quit);
  EXPECT_FALSE(std::filesystem::exists(folder + "/ball.stl"));
  std::filesystem::remove_all(folder);
}

// The next export of the same document is offered the last one's file, not the document's
// folder again (an artist's test: Enter would have written a second file in the wrong place);
// another document is offered its own.
TEST(ExportSettings, TheNextExportIsOfferedTheLastOnesPlace) {
  const std::string folder =
      std::filesystem::absolute(::testing::TempDir() + "/strata_export_place")
          .lexically_normal()
          .string();
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder + "/out");
  EditorState state;
  state.makeBackend = [] { return std::make_shared<CpuBackend>(); };
  addPrimitive(state, NodeKind::Sphere);
  ASSERT_TRUE(saveDocumentAs(state, folder + "/ball.strata.json"));
  EXPECT_EQ(exportSuggestion(state), folder + "/ball.stl");
  startExport(state, folder + "/out/ball.ply", 32, 0.0, false);
  ASSERT_TRUE(state.exportJob);
  state.exportJob.reset();  // waits for it
  EXPECT_EQ(exportSuggestion(state), folder + "/out/ball.ply");
  ASSERT_TRUE(saveDocumentAs(state, folder + "/other.strata.json"));
  EXPECT_EQ(exportSuggestion(state), folder + "/other.stl");
  // An untitled document: the last export's folder, a name of its own (not another untitled
  // document's file, which Enter would replace).
  EditorState untitled;
  untitled.lastExportPath = folder + "/out/ball.ply";
  EXPECT_EQ(exportSuggestion(untitled), folder + "/out/part.stl");
  EXPECT_EQ(dialogFolder(untitled), folder + "/out/");
  // The folder of the scene saved or opened last (the recent files, kept between runs) comes
  // before the export's: an artist's Save of an example's copy opened in the program's scenes/.
  std::filesystem::create_directories(folder + "/work");
  untitled.recentFiles = {folder + "/gone/old.strata.json", folder + "/work/last.strata.json"};
  EXPECT_EQ(dialogFolder(untitled), folder + "/work/");  // a folder that has gone is passed by
  EXPECT_EQ(saveAsSuggestion(untitled), folder + "/work/untitled.strata.json");
  // File > New after working on a file: that file's folder (Save As opened in $HOME).
  newDocument(state);
  EXPECT_EQ(dialogFolder(state), folder + "/");
  // The scene saved or opened last, kept between runs, before the document replaced.
  state.recentFiles = {folder + "/work/last.strata.json"};
  EXPECT_EQ(dialogFolder(state), folder + "/work/");
  state.recentFiles.clear();
  // Nothing written yet: the user's home, not the folder the editor was started in (an artist's
  // Save As opened in the program's own folder).
  const char* home = std::getenv("HOME");
  const std::string keptHome = home ? home : "";
  setenv("HOME", folder.c_str(), 1);
  EditorState fresh;
  EXPECT_EQ(dialogFolder(fresh), folder + "/");
  EXPECT_EQ(exportSuggestion(fresh), folder + "/part.stl");
  if (home)
    setenv("HOME", keptHome.c_str(), 1);
  else
    unsetenv("HOME");
  std::filesystem::remove_all(folder);
}

// The last export's folder is kept between runs (export.txt): the first export of an untitled
// document in a new run is offered it (an artist's first export of every run opened in $HOME), and
// so is a document whose own folder takes no file (here: gone since it was saved).
TEST(ExportSettings, TheLastExportsFolderIsOfferedInTheNextRun) {
  const std::string folder =
      std::filesystem::absolute(::testing::TempDir() + "/strata export folder")
          .lexically_normal()
          .string();
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder + "/prints");
  std::filesystem::create_directories(folder + "/scenes");
  const std::string settings = folder + "/export.txt";
  {  // a run that exports into prints/
    EditorState run;
    run.makeBackend = [] { return std::make_shared<CpuBackend>(); };
    run.exportSettingsPath = settings;
    addPrimitive(run, NodeKind::Sphere);
    startExport(run, folder + "/prints/ball.stl", 32, 0.0, false);
    ASSERT_TRUE(run.exportJob);
    run.exportJob.reset();  // waits for it
  }
  const ExportSettings kept = readExportSettings(settings, {});
  EXPECT_EQ(kept.folder, folder + "/prints");  // a folder with spaces comes back whole
  EditorState next;                            // the next run, as the editor starts it
  next.rememberedExportFolder = kept.folder;
  EXPECT_EQ(exportSuggestion(next), folder + "/prints/part.stl");
  EXPECT_EQ(dialogFolder(next), folder + "/prints/");
  // A document saved in scenes/, which has gone since: its export goes to prints/.
  addPrimitive(next, NodeKind::Box);
  ASSERT_TRUE(saveDocumentAs(next, folder + "/scenes/block.strata.json"));
  EXPECT_EQ(exportSuggestion(next), folder + "/scenes/block.stl");  // its own folder first
  std::filesystem::remove_all(folder + "/scenes");
  EXPECT_EQ(exportSuggestion(next), folder + "/prints/block.stl");
  // A folder that has gone is not offered.
  std::filesystem::remove_all(folder + "/prints");
  EXPECT_EQ(rememberedExportFolder(next), "");
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace strata::ui

namespace strata::ui {
namespace {

// The import dialog's folder, unit and up axis were kept within a run only: an artist importing
// a folder of scans browsed to it again after every restart. A folder with spaces comes back
// whole; a unit or axis out of range, or a folder that is gone, leaves the defaults.
TEST(ImportSettings, TheImportDialogsChoicesOutliveTheRun) {
  const std::string folder = ::testing::TempDir() + "/strata_import_settings";
  std::filesystem::remove_all(folder);
  const std::string scans = folder + "/my scans";
  std::filesystem::create_directories(scans);
  {
    EditorState state;
    state.importSettingsPath = folder + "/config/import.txt";
    state.lastImportFolder = scans;
    state.lastImportUnit = 2;
    state.lastImportUpAxis = 1;
    rememberImportChoices(state);
  }
  const ImportSettings back = readImportSettings(folder + "/config/import.txt", {});
  EXPECT_EQ(back.folder, scans);
  EXPECT_EQ(back.unit, 2);
  EXPECT_EQ(back.upAxis, 1);
  EditorState next;
  next.lastImportFolder = back.folder;
  EXPECT_EQ(importFolder(next), scans + "/");
  {
    std::ofstream out(folder + "/config/import.txt");
    out << "unit 999\nupAxis 2\nfolder " << folder << "/gone\n";
  }
  const ImportSettings bad = readImportSettings(folder + "/config/import.txt", {});
  EXPECT_EQ(bad.unit, 0);
  EXPECT_EQ(bad.upAxis, 0);
  next.lastImportFolder = bad.folder;
  EXPECT_NE(importFolder(next), folder + "/gone/") << "a folder that is gone is not offered";
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace strata::ui
