// resolveDialogPath: what the built-in browser's path field means. A name alone lies in the
// folder shown, a name saved without an extension gets the suggested one, a save into a missing
// folder and an open of a missing file are refused with a message naming them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ui/file_dialog.h"

namespace strata::ui {
namespace {

namespace fs = std::filesystem;

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
  const ResolvedPath r = resolveDialogPath("bracket", folder_.string(), true, ".stl");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.path, (folder_ / "bracket.stl").string());
  // An extension typed is kept; a relative folder is under the folder shown.
  EXPECT_EQ(resolveDialogPath("bracket.obj", folder_.string(), true, ".stl").path,
            (folder_ / "bracket.obj").string());
  EXPECT_EQ(resolveDialogPath("./x/../b", folder_.string(), true, ".ply").path,
            (folder_ / "b.ply").string());
  // An absolute path is taken as it is.
  EXPECT_EQ(resolveDialogPath((folder_ / "c.3mf").string(), "/nowhere", true, ".stl").path,
            (folder_ / "c.3mf").string());
}

TEST_F(DialogPath, MissingFoldersAndFilesAreRefusedByName) {
  const ResolvedPath save = resolveDialogPath("missing/part", folder_.string(), true, ".stl");
  EXPECT_EQ(save.path, "");
  EXPECT_NE(save.error.find((folder_ / "missing").string()), std::string::npos) << save.error;
  const ResolvedPath open = resolveDialogPath("nothing.stl", folder_.string(), false, "");
  EXPECT_EQ(open.path, "");
  EXPECT_NE(open.error.find("nothing.stl"), std::string::npos) << open.error;
  // Opening does not add an extension; an existing file opens.
  EXPECT_EQ(resolveDialogPath("part", folder_.string(), false, ".stl").path, "");
  EXPECT_EQ(resolveDialogPath("part.stl", folder_.string(), false, "").path,
            (folder_ / "part.stl").string());
  EXPECT_NE(resolveDialogPath("", folder_.string(), true, ".stl").error, "");
}

}  // namespace
}  // namespace strata::ui
