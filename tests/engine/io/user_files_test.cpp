// Recent files and the recovery file (engine/io/user_files.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "engine/io/document_files.h"
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

}  // namespace
}  // namespace strata
