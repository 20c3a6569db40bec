// Recent files and the recovery file (engine/io/user_files.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "engine/io/document_files.h"
#include "engine/io/recovery_slots.h"
#include "engine/io/user_files.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

std::string tempDir(const std::string& name) {
  fs::path dir = fs::path(testing::TempDir()) / ("strata_user_files_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

TEST(DocumentUserFiles, RecentFilesMostRecentFirstWithoutDuplicates) {
  std::string list = tempDir("recent") + "/config/recent.txt";
  EXPECT_TRUE(readRecentFiles(list).empty());
  addRecentFile(list, "/a/one.strata.json");
  addRecentFile(list, "/a/two.strata.json");
  auto files = addRecentFile(list, "/a/one.strata.json");
  EXPECT_EQ(files, (std::vector<std::string>{"/a/one.strata.json", "/a/two.strata.json"}));
  EXPECT_EQ(readRecentFiles(list), files);
  for (int i = 0; i < 20; ++i) addRecentFile(list, "/b/" + std::to_string(i) + ".strata.json");
  EXPECT_EQ(readRecentFiles(list).size(), kMaxRecentFiles);
  EXPECT_EQ(readRecentFiles(list).front(), "/b/19.strata.json");
}

TEST(DocumentUserFiles, FoldersFollowXdgVariables) {
  const char* oldConfig = std::getenv("XDG_CONFIG_HOME");
  std::string saved = oldConfig ? oldConfig : "";
  setenv("XDG_CONFIG_HOME", "/tmp/xdg-config", 1);
  EXPECT_EQ(defaultRecentFilesPath(), "/tmp/xdg-config/strata/recent.txt");
  if (oldConfig)
    setenv("XDG_CONFIG_HOME", saved.c_str(), 1);
  else
    unsetenv("XDG_CONFIG_HOME");
}

TEST(DocumentRecovery, RoundTripKeepsContentOriginAndMeshes) {
  std::string dir = tempDir("recovery");
  fs::create_directories(dir + "/project/meshes");
  fs::copy_file(std::string(STRATA_ASSETS) + "/meshes/bunny.obj",
                dir + "/project/meshes/bunny.obj");
  std::string recovery = dir + "/data/recovery.strata.json";

  Document doc;
  saveDocumentAs(doc, dir + "/project/part.strata.json");
  NodeId mesh = importMeshFile(doc, dir + "/project/meshes/bunny.obj");
  NodeId box = doc.addNode(NodeKind::Box);
  doc.rename(box, "unsaved change");
  EXPECT_FALSE(recoveryFileExists(recovery));
  writeRecoveryFile(doc, recovery);
  EXPECT_TRUE(recoveryFileExists(recovery));

  // The question at start names the document and when it was written.
  const RecoveryInfo info = describeRecoveryFile(recovery);
  EXPECT_EQ(info.origin, dir + "/project/part.strata.json");
  EXPECT_EQ(info.writtenAt.size(), std::string("2026-11-23 06:12").size()) << info.writtenAt;

  Document recovered = readRecoveryFile(recovery);
  EXPECT_TRUE(recovered.dirty());
  EXPECT_EQ(recovered.path(), dir + "/project/part.strata.json");
  EXPECT_EQ(findNode(recovered.root(), box)->name, "unsaved change");
  NodePtr m = findNode(recovered.root(), mesh);
  ASSERT_TRUE(m && m->mesh);
  EXPECT_EQ(m->meshPath,
            (fs::absolute(dir) / "project/meshes/bunny.obj").lexically_normal().generic_string());

  removeRecoveryFile(recovery);
  EXPECT_FALSE(recoveryFileExists(recovery));
  EXPECT_FALSE(fs::exists(recovery + ".origin"));
}

// A document opened by a relative path (the editor started in its folder) is recovered by its
// absolute one: an editor started elsewhere saves it where it came from.
TEST(DocumentRecovery, TheOriginIsAbsoluteWhereverTheEditorStarted) {
  const std::string dir = fs::absolute(tempDir("relative_origin")).lexically_normal().string();
  const std::string recovery = dir + "/data/recovery.strata.json";
  Document doc;
  const fs::path before = fs::current_path();
  fs::current_path(dir);
  saveDocumentAs(doc, "part.strata.json");
  doc.addNode(NodeKind::Box);
  writeRecoveryFile(doc, recovery);
  fs::current_path(before);
  EXPECT_EQ(describeRecoveryFile(recovery).origin, dir + "/part.strata.json");
  EXPECT_EQ(readRecoveryFile(recovery).path(), dir + "/part.strata.json");
}

TEST(DocumentRecovery, UntitledDocument) {
  std::string recovery = tempDir("untitled") + "/recovery.strata.json";
  Document doc;
  doc.addNode(NodeKind::Torus);
  writeRecoveryFile(doc, recovery);
  EXPECT_EQ(describeRecoveryFile(recovery).origin, "");
  Document recovered = readRecoveryFile(recovery);
  EXPECT_EQ(recovered.path(), "");
  EXPECT_TRUE(recovered.dirty());
  EXPECT_EQ(recovered.root()->children.size(), 1u);
}

// Several editors at once (engine/io/recovery_slots.h): each autosaves into a slot of its own;
// a running editor's slot is never offered to another; a clean end removes only its own slot; an
// editor that crashed (its slot's lock free, as the kernel leaves a dead process's) is offered,
// to one editor at a time; a discarded one is kept aside. One shared file let a second editor
// overwrite, offer and delete a running editor's autosave (an artist's test).
TEST(DocumentRecovery, EachEditorHasASlotAndOnlyTheWorkOfEditorsThatEndedIsOffered) {
  const std::string dir = tempDir("slots") + "/recovery";
  Document first, second;
  first.addNode(NodeKind::Box);
  second.addNode(NodeKind::Sphere);
  auto a = std::make_unique<RecoverySlot>(dir);
  auto b = std::make_unique<RecoverySlot>(dir);
  EXPECT_NE(a->path(), b->path());
  writeRecoveryFile(first, a->path());
  writeRecoveryFile(second, b->path());
  EXPECT_TRUE(claimOrphanedRecoveries(dir).empty()) << "two running editors: nothing to offer";
  // One ends cleanly: its slot goes, the other's stays.
  const std::string bPath = b->path();
  b.reset();
  EXPECT_FALSE(fs::exists(bPath));
  EXPECT_TRUE(fs::exists(a->path()));
  EXPECT_TRUE(claimOrphanedRecoveries(dir).empty());

  // An editor that was killed: its file and its lock file, the lock held by nobody.
  const std::string crashed = dir + "/999999-0.strata.json";
  writeRecoveryFile(second, crashed);
  { std::ofstream(crashed + ".lock").put('\n'); }
  std::vector<RecoveryOffer> offers = claimOrphanedRecoveries(dir);
  ASSERT_EQ(offers.size(), 1u);
  EXPECT_EQ(offers[0].path, crashed);
  EXPECT_TRUE(claimOrphanedRecoveries(dir).empty()) << "offered by one editor at a time";
  // Left for later: offered again.
  offers.clear();
  offers = claimOrphanedRecoveries(dir);
  ASSERT_EQ(offers.size(), 1u);
  // Discarded: moved aside, not deleted.
  const std::string kept = discardRecovery(offers[0], dir);
  offers.clear();
  EXPECT_FALSE(fs::exists(crashed));
  EXPECT_FALSE(fs::exists(crashed + ".lock"));
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(fs::path(kept).parent_path(), fs::path(dir) / "discarded");
  EXPECT_EQ(readRecoveryFile(kept).root()->children.at(0)->kind, NodeKind::Sphere);
  EXPECT_TRUE(claimOrphanedRecoveries(dir).empty());
  // The file of earlier versions is offered too; recovered, it is forgotten.
  const std::string legacy = tempDir("slots_legacy") + "/recovery.strata.json";
  writeRecoveryFile(first, legacy);
  offers = claimOrphanedRecoveries(dir, legacy);
  ASSERT_EQ(offers.size(), 1u);
  EXPECT_EQ(offers[0].path, legacy);
  forgetRecovery(offers[0]);
  EXPECT_FALSE(fs::exists(legacy));
  EXPECT_TRUE(fs::exists(a->path())) << "the running editor's slot is untouched throughout";
  // The lock an editor killed with nothing unsaved left is cleared; a running one's stays.
  { std::ofstream(dir + "/999998-0.strata.json.lock").put('\n'); }
  claimOrphanedRecoveries(dir);
  EXPECT_FALSE(fs::exists(dir + "/999998-0.strata.json.lock"));
  EXPECT_TRUE(fs::exists(a->path() + ".lock"));
}

// Discarded work is kept, the newest kKeptDiscards of it.
TEST(DocumentRecovery, TheLastDiscardsAreKept) {
  const std::string dir = tempDir("discards") + "/recovery";
  fs::create_directories(dir);
  Document doc;
  doc.addNode(NodeKind::Box);
  std::vector<std::string> kept;
  for (int i = 0; i < kKeptDiscards + 3; ++i) {
    const std::string path = dir + "/" + std::to_string(900000 + i) + "-0.strata.json";
    writeRecoveryFile(doc, path);
    std::vector<RecoveryOffer> offers = claimOrphanedRecoveries(dir);
    ASSERT_EQ(offers.size(), 1u);
    kept.push_back(discardRecovery(offers[0], dir));
    ASSERT_FALSE(kept.back().empty());
  }
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / "discarded"))
    files += e.path().string().size() > 12 &&
             e.path().string().compare(e.path().string().size() - 12, 12, ".strata.json") == 0;
  EXPECT_EQ(files, size_t(kKeptDiscards));
  EXPECT_TRUE(fs::exists(kept.back()));
}

// A document knows its file as it opened or saved it: a file written since by another editor is
// told (a second editor's save was overwritten without a word: an artist's test).
TEST(DocumentUserFiles, AFileWrittenSinceItWasOpenedIsTold) {
  const std::string path = tempDir("changed") + "/part.strata.json";
  Document doc;
  doc.addNode(NodeKind::Box);
  saveDocumentAs(doc, path);
  EXPECT_EQ(changedOnDisk(doc), "");
  Document other = openDocument(path);
  EXPECT_EQ(changedOnDisk(other), "");
  other.addNode(NodeKind::Sphere);
  saveDocument(other);  // another editor saves the same file
  const std::string said = changedOnDisk(doc);
  EXPECT_NE(said.find(path), std::string::npos) << said;
  EXPECT_NE(said.find("another editor or program"), std::string::npos) << said;
  EXPECT_EQ(changedOnDisk(other), "");
  saveDocumentAs(doc, path);  // overwritten on purpose: the stamp follows
  EXPECT_EQ(changedOnDisk(doc), "");
  EXPECT_NE(changedOnDisk(other), "");
  Document untitled;
  EXPECT_EQ(changedOnDisk(untitled), "");
}

}  // namespace
}  // namespace strata
