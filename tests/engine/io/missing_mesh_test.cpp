// A scene whose mesh file is missing (moved, sent without its meshes): the command line refuses
// it naming the file; the editor's documents open the rest of the work, the node kept without
// its mesh, evaluated as nothing, and saved with its path and hash as they were.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/document/commands.h"
#include "engine/io/document_files.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

// The demo scene copied into a fresh folder, without the bunny its "../meshes/bunny.obj" names.
struct DemoWithoutItsMesh {
  DemoWithoutItsMesh() {
    dir = fs::temp_directory_path() / ("strata_missing_mesh_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "scenes");
    path = (dir / "scenes" / "demo.strata.json").string();
    fs::copy_file(test::assetsDir() + "/scenes/demo.strata.json", path);
  }
  ~DemoWithoutItsMesh() { fs::remove_all(dir); }
  fs::path dir;
  std::string path;
};

NodeId idNamed(const NodePtr& root, const std::string& name) {
  for (NodeId id : treeOrder(root))
    if (findNode(root, id)->name == name) return id;
  return 0;
}

TEST(MissingMeshes, TheCommandLineRefusesTheSceneNamingTheFile) {
  DemoWithoutItsMesh demo;
  try {
    loadScene(demo.path);
    ADD_FAILURE() << "a scene with a missing mesh loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bunny.obj"), std::string::npos) << e.what();
  }
}

TEST(MissingMeshes, TheEditorOpensTheRestAndKeepsTheNodeAsItWas) {
  DemoWithoutItsMesh demo;
  std::vector<std::string> warnings;
  Document doc = openDocument(demo.path, &warnings);
  const NodeId bunny = idNamed(doc.root(), "bunny");
  ASSERT_NE(bunny, 0u);
  const NodePtr node = findNode(doc.root(), bunny);
  EXPECT_TRUE(meshMissing(*node));
  EXPECT_FALSE(doc.dirty());
  bool said = false;
  for (const std::string& w : warnings)
    said = said || (w.find("bunny") != std::string::npos &&
                    w.find("kept without its mesh") != std::string::npos &&
                    w.find("bunny.obj") != std::string::npos);
  EXPECT_TRUE(said) << (warnings.empty() ? "no warning" : warnings[0]);

  // Evaluated as nothing: the same result as the full demo with the bunny hidden.
  Scene withHiddenBunny = loadScene(test::assetsDir() + "/scenes/demo.strata.json");
  withHiddenBunny.root = editNode(withHiddenBunny.root, idNamed(withHiddenBunny.root, "bunny"),
                                  [](Node& n) { n.visible = false; });
  Scene opened = doc.scene();
  opened.settings.resolution = withHiddenBunny.settings.resolution = 64;
  const EvalResult missing = test::evaluateCpu(opened);
  const EvalResult hidden = test::evaluateCpu(withHiddenBunny);
  EXPECT_GT(missing.measure.volume, 0.0);
  EXPECT_DOUBLE_EQ(missing.measure.volume, hidden.measure.volume);

  // Saved, the node still names its file and the content it recorded.
  const std::string recordedHash = node->meshHash;
  EXPECT_FALSE(recordedHash.empty());
  const std::string saved = (demo.dir / "scenes" / "saved.strata.json").string();
  saveDocumentAs(doc, saved);
  std::ifstream in(saved);
  std::stringstream text;
  text << in.rdbuf();
  // (Beside the scene's folder a path is saved relative, as for every mesh: relativeMeshPaths.)
  EXPECT_NE(text.str().find("\"../meshes/bunny.obj\""), std::string::npos) << text.str();
  EXPECT_NE(text.str().find(recordedHash), std::string::npos);

  // Once the file is back, the saved scene opens whole.
  fs::create_directories(demo.dir / "meshes");
  fs::copy_file(test::assetsDir() + "/meshes/bunny.obj", demo.dir / "meshes" / "bunny.obj");
  Document back = openDocument(saved);
  EXPECT_FALSE(meshMissing(*findNode(back.root(), idNamed(back.root(), "bunny"))));
}

}  // namespace
}  // namespace strata
