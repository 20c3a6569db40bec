// resolveDialogPath: what the built-in browser's path field means. A name alone lies in the
// folder shown, a name saved without an extension the dialog takes gets the suggested one, a
// save into a missing folder or one that takes no file, a folder given as a file and an open of a
// missing file are refused with a message naming them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "ui/file_dialog.h"

namespace strata::ui {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kMeshes = {"stl", "obj", "ply", "3mf"};

class DialogPath : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ =
        fs::temp_directory_path() /
        ("strata_dialog_path_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
    fs::create_directories(folder_);
    std::ofstream(folder_ / "part.stl") << "solid\n";
  }
  void TearDown() override { fs::remove_all(folder_); }
  fs::path folder_;
};

TEST_F(DialogPath, ANameAloneIsSavedInTheFolderShownWithTheSuggestedExtension) {
  const ResolvedPath r = resolveDialogPath("bracket", folder_.string(), true, ".stl", kMeshes);
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.path, (folder_ / "bracket.stl").string());
  // An extension typed is kept; a relative folder is under the folder shown.
  EXPECT_EQ(resolveDialogPath("bracket.obj", folder_.string(), true, ".stl", kMeshes).path,
            (folder_ / "bracket.obj").string());
  EXPECT_EQ(resolveDialogPath("./x/../b", folder_.string(), true, ".ply", kMeshes).path,
            (folder_ / "b.ply").string());
  // A dot that is not a format's extension is part of the name; trailing dots go.
  EXPECT_EQ(resolveDialogPath("bracket_v1.2", folder_.string(), true, ".stl", kMeshes).path,
            (folder_ / "bracket_v1.2.stl").string());
  EXPECT_EQ(resolveDialogPath("name.", folder_.string(), true, ".stl", kMeshes).path,
            (folder_ / "name.stl").string());
  EXPECT_EQ(resolveDialogPath("LOUD.STL", folder_.string(), true, ".stl", kMeshes).path,
            (folder_ / "LOUD.STL").string());
  // Scenes: the compound extension.
  EXPECT_EQ(resolveDialogPath("plate", folder_.string(), true, ".strata.json", {"json"}).path,
            (folder_ / "plate.strata.json").string());
  // An absolute path is taken as it is.
  EXPECT_EQ(resolveDialogPath((folder_ / "c.3mf").string(), "/nowhere", true, ".stl", kMeshes).path,
            (folder_ / "c.3mf").string());
}

TEST_F(DialogPath, MissingFoldersAndFilesAreRefusedByName) {
  const ResolvedPath save =
      resolveDialogPath("missing/part", folder_.string(), true, ".stl", kMeshes);
  EXPECT_EQ(save.path, "");
  EXPECT_NE(save.error.find((folder_ / "missing").string()), std::string::npos) << save.error;
  EXPECT_EQ(save.missingFolder, (folder_ / "missing").string());  // offered to be created
  EXPECT_EQ(resolveDialogPath("part", folder_.string(), true, ".stl", kMeshes).missingFolder, "");
  const ResolvedPath open = resolveDialogPath("nothing.stl", folder_.string(), false, "", kMeshes);
  EXPECT_EQ(open.path, "");
  EXPECT_NE(open.error.find("nothing.stl"), std::string::npos) << open.error;
  // Opening does not add an extension; an existing file opens.
  EXPECT_EQ(resolveDialogPath("part", folder_.string(), false, ".stl", kMeshes).path, "");
  EXPECT_EQ(resolveDialogPath("part.stl", folder_.string(), false, "", kMeshes).path,
            (folder_ / "part.stl").string());
  EXPECT_NE(resolveDialogPath("", folder_.string(), true, ".stl", kMeshes).error, "");
  // A folder is not a file: "sub/" names no file; opening a folder is refused.
  fs::create_directories(folder_ / "sub");
  EXPECT_NE(resolveDialogPath("sub/", folder_.string(), true, ".stl", kMeshes).error, "");
  EXPECT_EQ(resolveDialogPath("sub/", folder_.string(), true, ".stl", kMeshes).path, "");
  EXPECT_NE(resolveDialogPath("..", folder_.string(), true, ".stl", kMeshes).error, "");
  const ResolvedPath folder = resolveDialogPath("sub", folder_.string(), false, "", kMeshes);
  EXPECT_NE(folder.error.find("folder"), std::string::npos) << folder.error;
}

// A folder that exists but takes no file (an artist's test: a read-only folder let the dialog
// close, and the export then failed where only the status bar said it) is refused in the dialog,
// named with why; opening from it is not affected. /proc takes no new file, even for root.
TEST_F(DialogPath, AFolderThatTakesNoFileIsRefusedBeforeTheDialogCloses) {
  const ResolvedPath save = resolveDialogPath("part", "/proc", true, ".stl", kMeshes);
  EXPECT_EQ(save.path, "");
  EXPECT_NE(save.error.find("cannot create a file in /proc: it takes no new files"),
            std::string::npos)
      << save.error;  // not "No such file or directory" of a folder that is there
  EXPECT_NE(save.error.find("choose another folder"), std::string::npos) << save.error;
  EXPECT_EQ(save.missingFolder, "");  // it exists: nothing to create
  EXPECT_EQ(resolveDialogPath("version", "/proc", false, "", kMeshes).error, "");
  // A writable folder leaves no probe behind.
  ASSERT_EQ(resolveDialogPath("part2", folder_.string(), true, ".stl", kMeshes).error, "");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator{}), 1);
  // part.stl only
}

}  // namespace
}  // namespace strata::ui
