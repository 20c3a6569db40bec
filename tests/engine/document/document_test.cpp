// The editable document (engine/document/document.h): every command as one undo step, the
// dirty flag, saving and loading.
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <fstream>

#include "engine/document/commands.h"
#include "engine/document/document.h"
#include "engine/io/document_files.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"
#include "engine/util/limits.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

std::string tempDir(const std::string& name) {
  fs::path dir = fs::path(testing::TempDir()) / ("strata_document_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::vector<NodeId> childIds(const NodePtr& node) {
  std::vector<NodeId> ids;
  for (const auto& c : node->children) ids.push_back(c->id);
  return ids;
}

TEST(Document, NewDocumentIsAnEmptyCleanUnion) {
  Document doc;
  EXPECT_EQ(doc.root()->kind, NodeKind::Union);
  EXPECT_TRUE(doc.root()->children.empty());
  EXPECT_FALSE(doc.dirty());
  EXPECT_FALSE(doc.canUndo());
  EXPECT_EQ(doc.title(), "untitled");
  EXPECT_EQ(doc.nextId(), 2u);
}

TEST(Document, EveryCommandIsOneUndoStep) {
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  NodeId sphere = doc.addNode(NodeKind::Sphere);
  EXPECT_EQ(box, 2u);
  EXPECT_EQ(sphere, 3u);
  NodeId group = doc.group({box, sphere}, NodeKind::Difference);
  doc.rename(box, "block");
  Transform t;
  t.translate = glm::dvec3(1, 2, 3);
  doc.setTransform(sphere, t);
  doc.setColor(box, glm::vec3(1, 0, 0));
  PrimitiveParams p;
  p.radius = 2.0;
  doc.setParams(sphere, p);
  doc.setVisible(sphere, false);
  doc.setOperation(group, NodeKind::Intersection);
  NodeId copy = doc.duplicate(box);
  doc.move(copy, doc.root()->id, 0);
  doc.setResolution(64);
  doc.remove(copy);
  EXPECT_TRUE(doc.dirty());

  const NodePtr final = doc.root();
  EXPECT_EQ(findNode(final, box)->name, "block");
  EXPECT_EQ(findNode(final, group)->kind, NodeKind::Intersection);
  EXPECT_FALSE(findNode(final, sphere)->visible);
  EXPECT_EQ(findNode(final, sphere)->params.radius, 2.0);
  EXPECT_EQ(findNode(final, sphere)->transform.translate, glm::dvec3(1, 2, 3));
  EXPECT_EQ(findNode(final, box)->color, glm::vec3(1, 0, 0));
  EXPECT_EQ(doc.scene().settings.resolution, 64);

  int steps = 0;
  while (doc.undo()) ++steps;
  EXPECT_EQ(steps, 13);  // the resolution's step among them
  EXPECT_EQ(doc.scene().settings.resolution, Document().scene().settings.resolution);
  EXPECT_TRUE(doc.root()->children.empty());
  EXPECT_FALSE(doc.dirty());  // the document it started as
  while (doc.redo()) {
  }
  EXPECT_EQ(doc.root(), final);  // redo restores the very same snapshot
  EXPECT_EQ(doc.scene().settings.resolution, 64);
}

// The resolution, saved with the document, is an undo step of its own (an artist's typed 100000
// cells was saved into the scene with no way back but typing the old value): changes in a row
// one step. Undoing the other steps, before it or after, leaves the resolution as set.
TEST(Document, TheResolutionIsAStepOfItsOwnThatOtherStepsKeep) {
  Document doc;
  const int start = doc.scene().settings.resolution;
  NodeId box = doc.addNode(NodeKind::Box);
  doc.rename(box, "block");
  doc.setResolution(start * 2);
  doc.setResolution(start * 4);  // the same step: a drag, or + clicked twice
  EXPECT_EQ(doc.undoLabel(), Document::kResolutionStep);
  doc.rename(box, "brick");
  EXPECT_TRUE(doc.dirty());
  ASSERT_TRUE(doc.undo());  // "brick"
  EXPECT_EQ(findNode(doc.root(), box)->name, "block");
  EXPECT_EQ(doc.scene().settings.resolution, start * 4);
  ASSERT_TRUE(doc.undo());  // both resolution changes
  EXPECT_EQ(doc.scene().settings.resolution, start);
  EXPECT_EQ(findNode(doc.root(), box)->name, "block");
  ASSERT_TRUE(doc.undo());  // "block"
  EXPECT_NE(findNode(doc.root(), box)->name, "block");
  EXPECT_EQ(doc.scene().settings.resolution, start);
  ASSERT_TRUE(doc.redo());
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(doc.scene().settings.resolution, start * 4);
  ASSERT_TRUE(doc.redo());
  EXPECT_EQ(findNode(doc.root(), box)->name, "brick");
  EXPECT_EQ(doc.scene().settings.resolution, start * 4);
  // Redone, the resolution's step is closed: a new change is a step of its own.
  ASSERT_TRUE(doc.undo());       // "brick"
  ASSERT_TRUE(doc.undo());       // the resolution
  ASSERT_TRUE(doc.redo());       // the resolution again
  doc.setResolution(start / 2);  // a new step (the redo of "brick" goes, as after any change)
  EXPECT_FALSE(doc.canRedo());
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(doc.scene().settings.resolution, start * 4);
  EXPECT_THROW(doc.setResolution(kMaxResolution + 1), Error);
  EXPECT_EQ(doc.scene().settings.resolution, start * 4);
}

// A snapped move that lands on -0.0 is stored as 0 (the inspector showed "-0").
TEST(Document, AZeroInATransformIsPositive) {
  Document doc;
  const NodeId box = doc.addNode(NodeKind::Box);
  Transform t;
  t.translate = glm::dvec3(-0.0, 1.0, -0.0);
  t.rotateDegrees = glm::dvec3(0.0, -0.0, 0.0);
  doc.setTransform(box, t);
  const Transform& kept = findNode(doc.root(), box)->transform;
  EXPECT_FALSE(std::signbit(kept.translate.x));
  EXPECT_FALSE(std::signbit(kept.translate.z));
  EXPECT_FALSE(std::signbit(kept.rotateDegrees.y));
  EXPECT_EQ(kept.translate.y, 1.0);
}

TEST(Document, RefusedCommandsChangeNothing) {
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  NodeId group = doc.addNode(NodeKind::Union);
  NodeId inner = doc.addNode(NodeKind::Sphere, group);
  const NodePtr before = doc.root();
  const uint64_t revision = doc.revision();
  EXPECT_THROW(doc.move(group, inner), Error);  // a leaf
  EXPECT_THROW(doc.move(group, group), Error);  // itself
  EXPECT_THROW(doc.remove(doc.root()->id), Error);
  PrimitiveParams bad;
  bad.size.x = -1.0;
  EXPECT_THROW(doc.setParams(box, bad), Error);
  EXPECT_THROW(doc.setParams(group, PrimitiveParams()), Error);
  EXPECT_THROW(doc.setColor(box, glm::vec3(2.0f)), Error);
  EXPECT_THROW(doc.rename(99, "x"), Error);
  EXPECT_EQ(doc.root(), before);
  EXPECT_EQ(doc.revision(), revision);
}

TEST(Document, AddingToALeafAddsBesideIt) {
  Document doc;
  NodeId a = doc.addNode(NodeKind::Box);
  NodeId b = doc.addNode(NodeKind::Box);
  NodeId c = doc.addNode(NodeKind::Cone, a);
  EXPECT_EQ(childIds(doc.root()), (std::vector<NodeId>{a, c, b}));
}

TEST(Document, DragIsOneUndoStep) {
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  doc.beginInteraction();
  for (int i = 1; i <= 20; ++i) {
    Transform t;
    t.translate.x = i;
    doc.setTransform(box, t);
  }
  doc.endInteraction();
  EXPECT_EQ(findNode(doc.root(), box)->transform.translate.x, 20.0);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(findNode(doc.root(), box)->transform.translate.x, 0.0);
  ASSERT_TRUE(doc.undo());  // the add
  EXPECT_FALSE(doc.canUndo());
}

// Escape during a drag: the document is as before it, clean if it was, with no undo step.
TEST(Document, ACancelledDragLeavesNoTraceAndNoUndoStep) {
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  const uint64_t before = doc.revision();
  const size_t steps = doc.canUndo() ? 1 : 0;
  doc.beginInteraction();
  for (int i = 1; i <= 5; ++i) {
    Transform t;
    t.translate.x = i;
    doc.setTransform(box, t);
  }
  doc.cancelInteraction();
  EXPECT_FALSE(doc.interacting());
  EXPECT_EQ(findNode(doc.root(), box)->transform.translate.x, 0.0);
  EXPECT_EQ(doc.revision(), before);
  EXPECT_EQ(doc.undoLabel().rfind("add", 0), 0u) << doc.undoLabel();  // the add, not a move
  ASSERT_EQ(steps, 1u);
  ASSERT_TRUE(doc.undo());
  EXPECT_FALSE(doc.canUndo());
  // A drag that changed nothing cancels to nothing.
  doc.beginInteraction();
  doc.cancelInteraction();
  EXPECT_FALSE(doc.interacting());
}

TEST(Document, DropOnEmptySpaceWrapsANonUnionRoot) {
  Scene scene;
  scene.root = makeOperationNode(
      NodeKind::Difference, 1,
      {makePrimitiveNode(NodeKind::Box, 2),
       makeOperationNode(NodeKind::Union, 3, {makePrimitiveNode(NodeKind::Sphere, 4)})});
  Document doc(scene);
  doc.moveToTop(4);
  EXPECT_EQ(doc.root()->kind, NodeKind::Union);
  EXPECT_EQ(doc.root()->id, 5u);
  EXPECT_EQ(childIds(doc.root()), (std::vector<NodeId>{1, 4}));
  doc.undo();
  EXPECT_EQ(doc.root()->id, 1u);
}

TEST(Document, SaveLoadRoundTripAndBackup) {
  std::string dir = tempDir("roundtrip");
  std::string path = dir + "/part.strata.json";
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  NodeId hole = doc.addNode(NodeKind::Cylinder);
  NodeId cut = doc.group({box, hole}, NodeKind::Difference);
  doc.rename(cut, "cut");
  Transform t;
  t.rotateDegrees = glm::dvec3(0, 90, 0);
  t.scale = glm::dvec3(1, 2, -1);
  doc.setTransform(hole, t);
  doc.setColor(box, glm::vec3(0.25f, 0.5f, 1.0f));
  doc.setResolution(48);
  EXPECT_THROW(saveDocument(doc), Error);  // no file yet
  saveDocumentAs(doc, path);
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(doc.title(), "part.strata.json");
  EXPECT_FALSE(fs::exists(path + ".bak"));

  Document loaded = openDocument(path);
  EXPECT_EQ(sceneToJson(loaded.scene()), sceneToJson(doc.scene()));
  EXPECT_FALSE(loaded.dirty());

  doc.rename(box, "block");
  EXPECT_EQ(doc.title(), "part.strata.json *");
  saveDocument(doc);
  ASSERT_TRUE(fs::exists(path + ".bak"));
  EXPECT_EQ(findNode(openDocument(path + ".bak").root(), box)->name, "box 2");
  EXPECT_EQ(findNode(openDocument(path).root(), box)->name, "block");
  doc.undo();
  EXPECT_TRUE(doc.dirty());
}

TEST(Document, MeshImportAndSaveAsElsewhereKeepsTheMeshFound) {
  std::string dir = tempDir("mesh");
  fs::create_directories(dir + "/meshes");
  fs::copy_file(std::string(STRATA_ASSETS) + "/meshes/bunny.obj", dir + "/meshes/bunny.obj");
  const std::string absolute =
      (fs::absolute(dir) / "meshes/bunny.obj").lexically_normal().generic_string();
  auto fileText = [](const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  Document doc;
  saveDocumentAs(doc, dir + "/scene.strata.json");
  NodeId mesh = importMeshFile(doc, dir + "/meshes/bunny.obj");
  NodePtr node = findNode(doc.root(), mesh);
  EXPECT_EQ(node->name, "bunny");
  EXPECT_EQ(node->meshPath, absolute);  // absolute in memory
  EXPECT_FALSE(node->meshHash.empty());
  ASSERT_TRUE(node->mesh);
  saveDocument(doc);
  // Written relative to the file's folder.
  EXPECT_NE(fileText(dir + "/scene.strata.json").find("\"meshes/bunny.obj\""), std::string::npos);
  EXPECT_EQ(findNode(openDocument(dir + "/scene.strata.json").root(), mesh)->meshPath, absolute);

  fs::create_directories(dir + "/other");
  doc.rename(mesh, "renamed");
  saveDocumentAs(doc, dir + "/other/copy.strata.json");
  // Beside the new folder (under a common one): written relative to it.
  EXPECT_NE(fileText(dir + "/other/copy.strata.json").find("\"../meshes/bunny.obj\""),
            std::string::npos);
  EXPECT_TRUE(findNode(openDocument(dir + "/other/copy.strata.json").root(), mesh)->mesh);
  // Undo after Save As elsewhere, then save: the mesh is still found from the new folder.
  ASSERT_TRUE(doc.undo());
  saveDocument(doc);
  Document again = openDocument(dir + "/other/copy.strata.json");
  EXPECT_TRUE(findNode(again.root(), mesh)->mesh);
  EXPECT_EQ(findNode(again.root(), mesh)->name, "bunny");
  EXPECT_THROW(importMeshFile(doc, dir + "/missing.obj"), Error);
  // An open mesh: refused unless accepted, then marked open, and a closed one accepted "open"
  // is not marked (nothing about it is guessed).
  {
    std::ofstream open(dir + "/open.obj");
    open << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n";
  }
  try {
    importMeshFile(doc, dir + "/open.obj");
    ADD_FAILURE() << "an open mesh was taken without being accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("open (boundary) edges"), std::string::npos) << e.what();
  }
  const NodeId open =
      importMeshFile(doc, dir + "/open.obj", 0, PlaceMode::Add, Transform{}, nullptr, true);
  EXPECT_TRUE(findNode(doc.root(), open)->meshOpen);
  const NodeId closed =
      importMeshFile(doc, dir + "/meshes/bunny.obj", 0, PlaceMode::Add, Transform{}, nullptr, true);
  EXPECT_FALSE(findNode(doc.root(), closed)->meshOpen);
  saveDocument(doc);
  EXPECT_TRUE(findNode(openDocument(dir + "/other/copy.strata.json").root(), open)->meshOpen);
  // The mark taken out of the file by hand: the node is kept without its mesh, says why (it was
  // shown as a file that could not be read), and can be taken as open again, one undo step.
  {
    std::ifstream in(dir + "/other/copy.strata.json");
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const size_t mark = text.find("\"open\": true,");
    ASSERT_NE(mark, std::string::npos) << text;
    text.erase(mark, std::string("\"open\": true,").size());
    std::ofstream(dir + "/other/unmarked.strata.json") << text;
  }
  Document unmarked = openDocument(dir + "/other/unmarked.strata.json");
  NodePtr kept = findNode(unmarked.root(), open);
  ASSERT_TRUE(kept && meshMissing(*kept));
  EXPECT_TRUE(kept->meshRefusedAsOpen);
  EXPECT_NE(kept->meshProblem.find("open (boundary) edges"), std::string::npos)
      << kept->meshProblem;
  acceptOpenMesh(unmarked, open);
  NodePtr taken = findNode(unmarked.root(), open);
  EXPECT_TRUE(taken->meshOpen);
  EXPECT_FALSE(meshMissing(*taken));
  EXPECT_EQ(unmarked.undoLabel(), "take as an open mesh");
  ASSERT_TRUE(unmarked.undo());
  EXPECT_TRUE(meshMissing(*findNode(unmarked.root(), open)));
  // A file that cannot be read at all is not taken.
  EXPECT_FALSE(findNode(openDocument(dir + "/other/unmarked.strata.json").root(), closed)
                   ->meshRefusedAsOpen);
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

// An undo names what it takes back: the position, rotation or scale, the parameter (it said
// "transform" and "parameters" whichever it was: an artist's test); several at once keep the
// general word.
TEST(Document, AnUndoNamesTheFieldItTakesBack) {
  Document doc;
  const NodeId box = doc.addNode(NodeKind::Box);
  Transform t = findNode(doc.root(), box)->transform;
  t.translate.x = 5.0;
  doc.setTransform(box, t);
  EXPECT_EQ(doc.undoLabel(), "position");
  t.scale = glm::dvec3(2.0);
  doc.setTransform(box, t);
  EXPECT_EQ(doc.undoLabel(), "scale");
  t.rotateDegrees.z = 30.0;
  t.translate.y = 1.0;
  doc.setTransform(box, t);
  EXPECT_EQ(doc.undoLabel(), "transform");
  const NodeId cone = doc.addNode(NodeKind::Cone);
  PrimitiveParams p = findNode(doc.root(), cone)->params;
  p.topRadius = 0.2;
  doc.setParams(cone, p);
  EXPECT_EQ(doc.undoLabel(), "top radius");
  p.height = 3.0;
  p.radius = 0.7;
  doc.setParams(cone, p);
  EXPECT_EQ(doc.undoLabel(), "parameters");
  // Kinds as people read them, not as files spell them ("make circularArray": an artist's test).
  const NodeId group = doc.group({cone}, NodeKind::CircularArray);
  EXPECT_EQ(doc.undoLabel(), "group as circular array");
  doc.setOperation(group, NodeKind::Union);
  doc.setOperation(group, NodeKind::CircularArray);
  EXPECT_EQ(doc.undoLabel(), "make circular array");
}

}  // namespace
}  // namespace strata
