// The import dialog's options (ui/import_options.h) and what importing and dropping from the
// palette do to the document (ui/editor_actions.h), without a window.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include <glm/geometric.hpp>

#include "engine/document/commands.h"
#include "engine/document/measurement.h"
#include "engine/document/roles.h"
#include "engine/kinds/primitives.h"
#include "engine/util/error.h"
#include "ui/editor_actions.h"
#include "ui/import_options.h"
#include "ui/pattern_guides.h"
#include "ui/scene_queries.h"
#include "ui/viewport.h"

namespace strata::ui {
namespace {

int unitIndex(const std::string& label) {
  const auto& units = importUnits();
  for (size_t i = 0; i < units.size(); ++i)
    if (label == units[i].label) return int(i);
  ADD_FAILURE() << "no unit " << label;
  return 0;
}

// A box with two holes cut in it (the palette in cut mode; the mode left at cut): the box, the
// cylinder and the sphere.
struct PlateWithTwoHoles {
  NodeId plate, first, second;
};
PlateWithTwoHoles plateWithTwoHoles(EditorState& state) {
  PlateWithTwoHoles made;
  made.plate = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  state.selection = {made.plate};
  made.first = addPrimitive(state, NodeKind::Cylinder);
  state.selection = {made.first};
  made.second = addPrimitive(state, NodeKind::Sphere);
  return made;
}

// A part of `kind` added (the palette's way) and then moved to `transform`, in one undo step each.
NodeId addPartAt(EditorState& state, NodeKind kind, const Transform& transform) {
  const NodeId id = addPrimitive(state, kind);
  EXPECT_TRUE(guarded(state, [&] { state.document.setTransform(id, transform); }));
  return id;
}

// A plate with a hole cut from it: the plate, the hole, and the difference holding both.
struct PlateWithHole {
  NodeId plate = 0, hole = 0, group = 0;
};
PlateWithHole addPlateWithHole(EditorState& state) {
  PlateWithHole p;
  p.plate = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  p.hole = addPrimitive(state, NodeKind::Cylinder);
  state.placeMode = PlaceMode::Add;
  NodeLocation where;
  if (locateNode(state.document.root(), p.hole, &where)) p.group = where.parent->id;
  clearSelection(state);
  return p;
}

TEST(ImportOptions, ScaleConvertsFileUnitsToSceneUnits) {
  std::string why;
  EXPECT_DOUBLE_EQ(importScale(unitIndex("scene units"), "millimetre", &why), 1.0);
  EXPECT_DOUBLE_EQ(importScale(unitIndex("millimetres"), "millimetre", &why), 1.0);
  EXPECT_DOUBLE_EQ(importScale(unitIndex("metres"), "millimetre", &why), 1000.0);
  EXPECT_DOUBLE_EQ(importScale(unitIndex("inches"), "mm", &why), 25.4);
  EXPECT_DOUBLE_EQ(importScale(unitIndex("millimetres"), "inch", &why), 1.0 / 25.4);
  EXPECT_DOUBLE_EQ(importScale(unitIndex("centimetres"), "metre", &why), 0.01);
  EXPECT_TRUE(why.empty()) << why;
  EXPECT_DOUBLE_EQ(importScale(unitIndex("metres"), "furlong", &why), 1.0);
  EXPECT_NE(why.find("furlong"), std::string::npos) << why;
}

// An empty scene's view spans about a tenth of a metre in its unit (at least one unit), so that
// a millimetre scene's first box is 25 mm, not 2 (its view showed 8 units whatever they were).
TEST(ImportOptions, AnEmptySceneIsSeenAtAHandsSpanInItsUnit) {
  EXPECT_DOUBLE_EQ(emptySceneSpan("millimetre"), 100.0);
  EXPECT_DOUBLE_EQ(emptySceneSpan("mm"), 100.0);
  EXPECT_NEAR(emptySceneSpan("cm"), 10.0, 1e-9);
  EXPECT_NEAR(emptySceneSpan("inch"), 100.0 / 25.4, 1e-9);
  EXPECT_DOUBLE_EQ(emptySceneSpan("metre"), 1.0);
  EXPECT_DOUBLE_EQ(emptySceneSpan("furlong"), 10.0);
  EditorState state;
  ASSERT_EQ(sceneUnitMetres(state.document.scene().settings.unit), 0.001);
  Viewport view;
  view.viewAll(state);
  const double shown = view.camera.unitsPerPixel(600.0) * 600.0;
  EXPECT_GT(shown, 60.0);
  EXPECT_LT(shown, 140.0);
}

TEST(ImportOptions, YUpTurnsPlusYOntoPlusZ) {
  const glm::dmat4 m = importTransform(2.0, 1).matrix();
  const glm::dvec3 y = glm::dvec3(m * glm::dvec4(0, 1, 0, 0));
  EXPECT_NEAR(glm::distance(y, glm::dvec3(0, 0, 2)), 0.0, 1e-12);
  const glm::dvec3 z = glm::dvec3(m * glm::dvec4(0, 0, 1, 0));
  EXPECT_NEAR(glm::distance(z, glm::dvec3(0, -2, 0)), 0.0, 1e-12);  // still right-handed
  EXPECT_EQ(importTransform(3.0, 0).rotateDegrees, glm::dvec3(0.0));
}

// File > Open on an STL said "line 17, column 991775: JSON nested more than 1040 levels deep":
// a mesh opened as a scene is refused by what it is, and the document is kept.
TEST(ImportAndPlace, AMeshOpenedAsASceneIsRefusedByWhatItIs) {
  EditorState state;
  const NodeId kept = addPrimitive(state, NodeKind::Box);
  const std::string mesh = std::string(STRATA_ASSETS) + "/meshes/bunny.obj";
  EXPECT_FALSE(openDocument(state, mesh));
  ASSERT_FALSE(state.log.empty());
  EXPECT_NE(state.log.back().text.find("a mesh, not a scene"), std::string::npos)
      << state.log.back().text;
  EXPECT_NE(state.log.back().text.find("Import mesh"), std::string::npos);
  EXPECT_TRUE(findNode(state.document.root(), kept));
}

// A scene shipped with Strata opened with File > Open (or Recent, or on the command line) is an
// untitled copy, as the demo is, so that Ctrl+S cannot change the shipped file (an artist's
// did); the same file elsewhere opens as itself.
TEST(ImportAndPlace, ABundledSceneOpensAsAnUntitledCopy) {
  EditorState state;
  state.bundledScenesFolder = std::string(STRATA_ASSETS) + "/scenes";
  const std::string shipped = state.bundledScenesFolder + "/two_spheres.strata.json";
  ASSERT_TRUE(openDocument(state, shipped));
  EXPECT_TRUE(state.document.path().empty());
  EXPECT_EQ(state.templateName, "two_spheres.strata.json");
  EXPECT_NE(state.log.back().text.find("shipped with Strata"), std::string::npos)
      << state.log.back().text;
  EXPECT_FALSE(state.document.root()->children.empty());
  // Save as offers the shipped file's name, not "untitled", in a folder of the user's.
  const std::string offered = saveAsSuggestion(state);
  EXPECT_NE(offered.find("two_spheres.strata.json"), std::string::npos) << offered;
  EXPECT_EQ(offered.find("/scenes/"), std::string::npos) << offered;
  // Through a path with ".." in it: the same folder.
  ASSERT_TRUE(
      openDocument(state, state.bundledScenesFolder + "/../scenes/two_spheres.strata.json"));
  EXPECT_TRUE(state.document.path().empty());

  const std::string folder = ::testing::TempDir() + "/strata_own_copy";
  std::filesystem::create_directories(folder);
  const std::string own = folder + "/two_spheres.strata.json";
  std::filesystem::copy_file(shipped, own, std::filesystem::copy_options::overwrite_existing);
  ASSERT_TRUE(openDocument(state, own));
  EXPECT_EQ(state.document.path(), own);
  EXPECT_TRUE(state.templateName.empty());
}

// A part dropped on a flat top got turns of a few thousandths of a degree ("-0.00" in the
// inspector) from the picked normal's encoding: a normal that close to an axis is the axis; a
// surface truly at a slant still turns the part.
TEST(ImportAndPlace, ADropOnAFlatFaceLeavesThePartUnturned) {
  EditorState state;
  const glm::dvec3 nearlyUp = glm::normalize(glm::dvec3(3e-5, -2e-5, 1.0));
  const NodeId flat =
      addPrimitiveAt(state, NodeKind::Box, Placement{glm::dvec3(1, 2, 3), false, nearlyUp});
  const Transform t = findNode(state.document.root(), flat)->transform;
  EXPECT_EQ(t.rotateDegrees, glm::dvec3(0.0));
  EXPECT_EQ(t.scale, glm::dvec3(1.0));
  // The status gives the contact point and the centre the inspector's move fields show.
  ASSERT_FALSE(state.log.empty());
  char centre[96];
  std::snprintf(centre, sizeof(centre), "its centre at (%.4g, %.4g, %.4g)", t.translate.x,
                t.translate.y, t.translate.z);
  EXPECT_NE(state.log.back().text.find("touching the surface at (1, 2, 3)"), std::string::npos)
      << state.log.back().text;
  EXPECT_NE(state.log.back().text.find(centre), std::string::npos) << state.log.back().text;
  EXPECT_NE(t.translate, glm::dvec3(1, 2, 3));  // it rests on the point: its centre lies above
  const glm::dvec3 slant = glm::normalize(glm::dvec3(0.0, 0.1, 1.0));
  const NodeId turned =
      addPrimitiveAt(state, NodeKind::Box, Placement{glm::dvec3(1, 2, 3), false, slant});
  EXPECT_GT(glm::length(findNode(state.document.root(), turned)->transform.rotateDegrees), 5.0);
}

TEST(ImportAndPlace, ImportWithOptionsIsOneUndoStep) {
  EditorState state;
  PendingImport import;
  import.path = std::string(STRATA_ASSETS) + "/meshes/bunny.obj";
  import.unit = unitIndex("metres");  // the scene is in millimetres
  import.upAxis = 1;
  import.placement = Placement{glm::dvec3(10.0, 20.0, 30.0), false, std::nullopt};
  NodeId id = importMesh(state, import);
  ASSERT_NE(id, 0u);
  NodePtr node = findNode(state.document.root(), id);
  ASSERT_TRUE(node);
  EXPECT_EQ(node->kind, NodeKind::Mesh);
  EXPECT_EQ(node->transform.scale, glm::dvec3(1000.0));
  EXPECT_EQ(node->transform.rotateDegrees, glm::dvec3(90.0, 0.0, 0.0));
  const Bounds b = selectionBounds(state.document.root(), {id});
  EXPECT_NEAR(glm::distance(b.center(), glm::dvec3(10.0, 20.0, 30.0)), 0.0, 1e-6);
  EXPECT_EQ(state.selection, std::vector<NodeId>{id});
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), id));
}

TEST(ImportAndPlace, ABadMeshFileIsReportedAndNothingIsAdded) {
  EditorState state;
  PendingImport import;
  import.path = "/nonexistent/part.stl";
  EXPECT_EQ(importMesh(state, import), 0u);
  EXPECT_TRUE(state.document.root()->children.empty());
  ASSERT_FALSE(state.log.empty());
  EXPECT_NE(state.log.back().text.find("/nonexistent/part.stl"), std::string::npos);
  EXPECT_FALSE(state.document.canUndo());
}

TEST(ImportAndPlace, DroppedPrimitiveIsCentredOnTheSurfacePointOrRestsOnTheGround) {
  EditorState state;
  NodeId group = addOperation(state, NodeKind::Union);
  // A parent transform: placement is in world space whatever the parent does.
  Transform parent;
  parent.translate = glm::dvec3(5.0, 0.0, 0.0);
  parent.rotateDegrees = glm::dvec3(0.0, 0.0, 90.0);
  parent.scale = glm::dvec3(2.0);
  ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(group, parent); }));
  selectNode(state, group);
  NodeId onSurface =
      addPrimitiveAt(state, NodeKind::Sphere, {glm::dvec3(1.0, 2.0, 3.0), false, std::nullopt});
  ASSERT_NE(onSurface, 0u);
  Bounds b = selectionBounds(state.document.root(), {onSurface});
  EXPECT_NEAR(glm::distance(b.center(), glm::dvec3(1.0, 2.0, 3.0)), 0.0, 1e-9);
  selectNode(state, group);
  NodeId onGround =
      addPrimitiveAt(state, NodeKind::Cylinder, {glm::dvec3(-4.0, 1.0, 0.0), true, std::nullopt});
  b = selectionBounds(state.document.root(), {onGround});
  EXPECT_NEAR(b.min.z, 0.0, 1e-9);
  EXPECT_NEAR(b.center().x, -4.0, 1e-9);
  EXPECT_NEAR(b.center().y, 1.0, 1e-9);
  // Each drop is one undo step.
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), onGround));
  EXPECT_TRUE(findNode(state.document.root(), onSurface));
}

// A part dropped on a surface turns its own +z to the surface's normal (under a turned, scaled
// parent too) and is centred on the point; one undo step.
TEST(ImportAndPlace, ADropOnASurfaceFacesItsNormal) {
  EditorState state;
  NodeId group = addOperation(state, NodeKind::Union);
  Transform parent;
  parent.rotateDegrees = glm::dvec3(0.0, 0.0, 90.0);
  parent.scale = glm::dvec3(2.0);
  ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(group, parent); }));
  for (const glm::dvec3& normal :
       {glm::dvec3(1.0, 0.0, 0.0), glm::normalize(glm::dvec3(0.0, -1.0, 1.0)),
        glm::dvec3(0.0, 0.0, -1.0), glm::dvec3(0.0, 0.0, 1.0)}) {
    selectNode(state, group);
    const NodeId id =
        addPrimitiveAt(state, NodeKind::Cylinder, {glm::dvec3(3.0, -1.0, 2.0), false, normal});
    const glm::dmat4 world = nodeWorldMatrix(state.document.root(), id);
    const glm::dvec3 axis = glm::normalize(glm::dvec3(world * glm::dvec4(0.0, 0.0, 1.0, 0.0)));
    EXPECT_NEAR(glm::distance(axis, normal), 0.0, 1e-9) << normal.x << normal.y << normal.z;
    // It adds material: it rests on the surface, its centre over the point (it sat half buried:
    // an artist's test), half its world height (the group scales by 2) along the normal.
    const Bounds b = selectionBounds(state.document.root(), {id});
    const double halfHeight = findNode(state.document.root(), id)->params.height;
    EXPECT_NEAR(glm::distance(b.center(), glm::dvec3(3.0, -1.0, 2.0) + halfHeight * normal), 0.0,
                1e-9);
    const size_t before = state.document.root()->children.size();
    undo(state);
    EXPECT_FALSE(findNode(state.document.root(), id));
    EXPECT_EQ(state.document.root()->children.size(), before);
  }
}

// A cutter dropped on a surface is centred on the point (half in, half out: a drill's depth),
// and a drop on a part's surface goes onto that part (a cut cuts it), not onto the selection:
// with nothing selected it cut the whole scene (an artist's test).
TEST(ImportAndPlace, ACutterDroppedOnAPartCutsThatPartCentredOnThePoint) {
  EditorState state;
  const NodeId plate = addPrimitive(state, NodeKind::Box);
  const NodeId other = addPrimitive(state, NodeKind::Sphere);
  NodeLocation was;
  ASSERT_TRUE(locateNode(state.document.root(), other, &was));
  clearSelection(state);
  state.placeMode = PlaceMode::Cut;
  Placement on{glm::dvec3(0.2, 0.1, 0.5), false, glm::dvec3(0.0, 0.0, 1.0)};
  on.part = plate;
  const NodeId hole = addPrimitiveAt(state, NodeKind::Cylinder, on);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  NodeLocation at;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &at));
  EXPECT_TRUE(isInSubtree(state.document.root(), at.parent->id, plate)) << "it cuts the plate";
  EXPECT_FALSE(isInSubtree(state.document.root(), at.parent->id, other)) << "not the sphere";
  EXPECT_EQ(roleOf(state.document.root(), other), ChildRole::Add);
  const Bounds b = selectionBounds(state.document.root(), {hole});
  EXPECT_NEAR(glm::distance(b.center(), on.point), 0.0, 1e-9);
}

// A cutter dropped on a small part beside a large one is sized from the part it lands on (at
// most a quarter of it), not from the scene: sized to a quarter of the scene it swallowed the
// part whole (an artist's test). A drop on the ground keeps the scene's size.
TEST(ImportAndPlace, APartDroppedOnASmallPartIsSizedFromThatPart) {
  EditorState state;
  const NodeId plate = addPrimitive(state, NodeKind::Box);
  Transform wide;
  wide.scale = glm::dvec3(100.0, 100.0, 5.0);
  ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(plate, wide); }));
  const NodeId pin = addPrimitive(state, NodeKind::Cylinder);
  PrimitiveParams thin = findNode(state.document.root(), pin)->params;
  thin.radius = 1.0;
  thin.height = 14.0;  // a quarter is 3.5, which rounds to 5 (more than a quarter): 2
  ASSERT_TRUE(guarded(state, [&] { state.document.setParams(pin, thin); }));
  clearSelection(state);
  const Bounds pinBox = selectionBounds(state.document.root(), {pin});
  state.placeMode = PlaceMode::Cut;
  Placement on{pinBox.center() + glm::dvec3(0.0, 0.0, 0.5 * pinBox.size().z), false,
               glm::dvec3(0.0, 0.0, 1.0)};
  on.part = pin;
  const NodeId hole = addPrimitiveAt(state, NodeKind::Cylinder, on);
  const Bounds holeBox = selectionBounds(state.document.root(), {hole});
  EXPECT_LE(std::max({holeBox.size().x, holeBox.size().y, holeBox.size().z}),
            std::max({pinBox.size().x, pinBox.size().y, pinBox.size().z}) / 4.0 + 1e-9);
  bool said = false;  // "... (1 mm, a quarter of cylinder ...)", before where it was placed
  for (const auto& line : state.log)
    said = said || line.text.find("a quarter of cyl") != std::string::npos;
  EXPECT_TRUE(said) << state.log.back().text;
  undo(state);
  // On the ground (no part): the scene's quarter.
  Placement ground{glm::dvec3(300.0, 0.0, 0.0), true, std::nullopt};
  const NodeId far = addPrimitiveAt(state, NodeKind::Box, ground);
  const Bounds farBox = selectionBounds(state.document.root(), {far});
  EXPECT_GT(farBox.size().x, pinBox.size().x);
  undo(state);
}

// A group made around parts far from its parent's origin has its origin at their centre (its
// gizmo sat at the world's origin, away from everything it holds: an artist's test); nothing
// moves in the world, the parts' places are kept relative to it, and its gizmo turns it about
// its own axes; one undo step.
TEST(ImportAndPlace, AGroupMadeAroundPartsHasItsOriginAtTheirCentre) {
  EditorState state;
  Transform far;
  far.translate = glm::dvec3(40.0, -30.0, 5.0);
  far.rotateDegrees = glm::dvec3(0.0, 0.0, 30.0);
  const NodeId pin = addPartAt(state, NodeKind::Cylinder, far);
  const glm::dmat4 pinWorld = nodeWorldMatrix(state.document.root(), pin);
  const Bounds before = selectionBounds(state.document.root(), {pin});
  state.selection = {pin};
  groupSelection(state, NodeKind::Union);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId group = state.selection[0];
  ASSERT_NE(group, pin);
  ASSERT_TRUE(isInSubtree(state.document.root(), group, pin));
  const NodePtr& root = state.document.root();
  EXPECT_NEAR(glm::distance(findNode(root, group)->transform.translate, before.center()), 0.0,
              1e-9);
  const glm::dmat4 pinNow = nodeWorldMatrix(root, pin);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(pinNow[c][r], pinWorld[c][r], 1e-9);
  Viewport viewport;
  glm::dmat4 parentWorld(1.0);
  Transform at;
  bool pivot = true;
  state.pivotAtSelectionCentre = true;
  ASSERT_TRUE(viewport.gizmoPlacement(state, &parentWorld, &at, &pivot));
  EXPECT_FALSE(pivot) << "the group's own gizmo, its own axes";
  EXPECT_NEAR(
      glm::distance(glm::dvec3(parentWorld * glm::dvec4(at.translate, 1.0)), before.center()), 0.0,
      1e-9);
  undo(state);  // one step: the group and its origin
  EXPECT_FALSE(findNode(state.document.root(), group));
  EXPECT_EQ(findNode(state.document.root(), pin)->transform.translate, far.translate);
}

// What a drop on a surface goes onto: the part whose material the surface bounds (a hole's wall
// is its cutter's surface: a boss dropped there became a cutter, a review found), and a part in
// a pattern its pattern (a drop on one copy was repeated in every copy).
TEST(ImportAndPlace, ADropOnAHolesWallGoesOntoThePartAroundIt) {
  EditorState state;
  const auto [plate, hole, second] = plateWithTwoHoles(state);
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodePtr& root = state.document.root();
  EXPECT_EQ(dropTargetFor(root, plate), plate);
  EXPECT_EQ(dropTargetFor(root, hole), where.parent->id);
  EXPECT_EQ(dropTargetFor(root, second), where.parent->id);
  EXPECT_EQ(dropTargetFor(root, 9999), 0u);
  state.placeMode = PlaceMode::Add;
  clearSelection(state);
  const NodeId array = addOperation(state, NodeKind::Array);
  state.selection = {array};
  const NodeId peg = addPrimitive(state, NodeKind::Cylinder);
  ASSERT_TRUE(isInSubtree(state.document.root(), array, peg));
  EXPECT_EQ(dropTargetFor(state.document.root(), peg), array);
}

// Align to the active part (min, centre, max on each axis) and drop to ground: every other
// selected part moves, a part inside a selected group moves only with it, one undo step each.
TEST(ImportAndPlace, AlignToTheActivePartAndDropToGround) {
  EditorState state;
  const NodeId a = addPrimitive(state, NodeKind::Box);
  const NodeId b = addPrimitive(state, NodeKind::Sphere);
  const NodeId c = addPrimitive(state, NodeKind::Box);
  auto place = [&](NodeId id, glm::dvec3 at) {
    Transform t;
    t.translate = at;
    ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(id, t); }));
  };
  place(a, {0.0, 0.0, 5.0});
  place(b, {7.0, -3.0, 9.0});
  place(c, {-4.0, 6.0, -2.0});
  auto boundsOf = [&](NodeId id) { return selectionBounds(state.document.root(), {id}); };
  state.selection = {b, c, a};  // a is active (the last clicked)
  alignSelection(state, 0, AlignEdge::Min);
  EXPECT_NEAR(boundsOf(b).min.x, boundsOf(a).min.x, 1e-9);
  EXPECT_NEAR(boundsOf(c).min.x, boundsOf(a).min.x, 1e-9);
  EXPECT_NEAR(boundsOf(b).center().y, -3.0, 1e-9);  // other axes untouched
  alignSelection(state, 2, AlignEdge::Max);
  EXPECT_NEAR(boundsOf(b).max.z, boundsOf(a).max.z, 1e-9);
  alignSelection(state, 1, AlignEdge::Centre);
  EXPECT_NEAR(boundsOf(c).center().y, boundsOf(a).center().y, 1e-9);
  undo(state);
  EXPECT_NEAR(boundsOf(c).center().y, 6.0, 1e-9);  // one step
  dropSelectionToGround(state);
  for (NodeId id : {a, b, c}) EXPECT_NEAR(boundsOf(id).min.z, 0.0, 1e-9);
  undo(state);
  EXPECT_GT(boundsOf(a).min.z, 1.0);
  // A selected group and a part inside it: the group drops, the part goes with it only.
  place(b, {7.0, -3.0, -6.0});  // below the box
  state.selection = {a, b};
  groupSelection(state, NodeKind::Union);
  const NodeId group = primarySelection(state);
  state.selection = {a, group};
  const double groupLow = boundsOf(group).min.z, boxLow = boundsOf(a).min.z;
  dropSelectionToGround(state);
  EXPECT_NEAR(boundsOf(group).min.z, 0.0, 1e-9);
  EXPECT_NEAR(boundsOf(a).min.z, boxLow - groupLow, 1e-9);  // moved with the group only
  // Aligning a group to a part inside it: the group holds the target, it does not move.
  const Bounds before = boundsOf(group);
  state.selection = {group, a};
  alignSelection(state, 0, AlignEdge::Max);
  EXPECT_EQ(boundsOf(group).min, before.min);
}

// A round made from the selection takes 3% of the parts' largest side, but at most a quarter of
// their thinnest wall (a round of r removes walls thinner than 2r): an open box of 100 mm with
// 3 mm walls gets a radius under 1 mm, not 3 mm (which removed every wall of an artist's cup),
// and the log says why; a solid block keeps the 3%.
TEST(ImportAndPlace, ARoundOfTheSelectionKeepsItsThinnestWalls) {
  EditorState state;
  const NodeId outer = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  const NodeId inner = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Add;
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams p;
    p.size = glm::dvec3(60.0, 60.0, 100.0);
    state.document.setParams(outer, p);
    p.size = glm::dvec3(54.0, 54.0, 100.0);
    state.document.setParams(inner, p);
    Transform t = findNode(state.document.root(), outer)->transform;
    t.translate.z += 3.0;  // a 3 mm floor
    state.document.setTransform(inner, t);
  }));
  std::vector<const Node*> path;
  ASSERT_TRUE(pathToNode(state.document.root(), inner, &path));
  const NodeId cup = path[path.size() - 2]->id;  // the difference
  state.selection = {cup};
  groupSelection(state, NodeKind::Round);
  NodePtr round = findNode(state.document.root(), state.selection[0]);
  ASSERT_EQ(round->kind, NodeKind::Round);
  EXPECT_LE(round->amount, 0.25 * 3.5);
  EXPECT_GE(round->amount, 0.25 * 2.0);
  EXPECT_NE(state.log.back().text.find("a quarter of the thinnest wall"), std::string::npos)
      << state.log.back().text;
  undo(state);

  state.selection = {outer};  // the block alone, walls of 60 mm: 3% of 100
  ASSERT_TRUE(guarded(state, [&] { state.document.remove(inner); }));
  groupSelection(state, NodeKind::Round);
  EXPECT_DOUBLE_EQ(findNode(state.document.root(), state.selection[0])->amount, 3.0);
}

// The demo's trap, and the modes: a part added onto the base of a difference with the palette
// in "add" mode adds material (it does not become a cutter); in "cut" mode it cuts; a paste
// does what its original did; a drag onto a cutter with Ctrl held cuts beside it, and the
// drop's tooltip sentence says so before the release. Each is one undo step.
TEST(Roles, NewPastedAndDroppedPartsDoWhatTheModeSays) {
  EditorState state;
  NodeId plate = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  NodeId hole = addPrimitive(state, NodeKind::Cylinder);  // onto the selected plate: cuts it
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  EXPECT_EQ(roleOf(state.document.root(), plate), ChildRole::Base);
  EXPECT_NE(state.log.back().text.find("cuts from"), std::string::npos) << state.log.back().text;

  state.placeMode = PlaceMode::Add;
  state.selection = {plate};
  NodeId rib = addPrimitive(state, NodeKind::Box);
  EXPECT_EQ(roleOf(state.document.root(), rib), ChildRole::Add);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);   // unchanged
  EXPECT_EQ(roleOf(state.document.root(), plate), ChildRole::Add);  // inside the new base union

  // Copy the hole, paste onto it in cut mode: a second cutter beside it.
  state.selection = {hole};
  copySelection(state);
  state.placeMode = PlaceMode::Cut;
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId pasted = state.selection[0];
  EXPECT_NE(pasted, hole);
  EXPECT_EQ(roleOf(state.document.root(), pasted), ChildRole::Cut);
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), pasted));

  // Drag the rib onto the hole with Ctrl: it becomes a cutter, the sentence says so first.
  const PlaceMode mode = dropMode(state, 2);
  EXPECT_EQ(mode, PlaceMode::Cut);
  bool refused = true;
  const std::string sentence = placementSentence(state, hole, mode, rib, &refused);
  EXPECT_FALSE(refused);
  EXPECT_NE(sentence.find("cuts from"), std::string::npos) << sentence;
  dropNode(state, rib, hole, mode);
  EXPECT_EQ(roleOf(state.document.root(), rib), ChildRole::Cut);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  undo(state);
  EXPECT_EQ(roleOf(state.document.root(), rib), ChildRole::Add);

  // A drop into the dragged node's own subtree is refused before the release, with a reason.
  const NodeId root = state.document.root()->id;
  placementSentence(state, rib, PlaceMode::Add, root, &refused);
  EXPECT_TRUE(refused);
}

// An artist's report: with the palette on "add", a cutter dragged onto another row or pasted
// became a solid and filled its hole. Moved and pasted parts keep their role unless a modifier
// picks another (Ctrl cut, Shift intersect, Alt add); new parts from the palette take its mode.
TEST(Roles, MovedAndPastedPartsKeepTheirRoleWhateverThePaletteSays) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  state.selection = {plate};
  const NodeId rib = addPrimitive(state, NodeKind::Box);
  ASSERT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  ASSERT_EQ(state.placeMode, PlaceMode::Add);
  // Dragged with no modifier: it keeps cutting, wherever it lands; the sentence says so.
  EXPECT_EQ(dropMode(state, 0, hole), PlaceMode::Cut);
  EXPECT_EQ(dropMode(state, 0, rib), PlaceMode::Add);
  EXPECT_EQ(dropMode(state, 0), PlaceMode::Add);  // a palette item: the palette's mode
  EXPECT_EQ(dropMode(state, kDropAdd, hole), PlaceMode::Add);
  EXPECT_EQ(dropMode(state, kDropIntersect, hole), PlaceMode::Intersect);
  EXPECT_EQ(dropMode(state, kDropCut, rib), PlaceMode::Cut);
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodeId difference = where.parent->id;
  bool refused = true;
  const std::string sentence =
      placementSentence(state, difference, dropMode(state, 0, hole), hole, &refused);
  EXPECT_FALSE(refused);
  EXPECT_NE(sentence.find("cuts"), std::string::npos) << sentence;
  dropNode(state, hole, difference, dropMode(state, 0, hole));
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  // Copied and pasted with the palette on "add": the copy cuts too.
  state.selection = {hole};
  copySelection(state);
  state.selection = {hole};
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  EXPECT_EQ(roleOf(state.document.root(), state.selection[0]), ChildRole::Cut);
  EXPECT_TRUE(removesMaterial(state.document.root(), state.selection[0]));
  // And a copy of the rib, pasted onto the hole, adds (into a new union in the hole's place:
  // inside a cutter, its material is taken away, and the log says so).
  state.selection = {rib};
  copySelection(state);
  state.selection = {hole};
  pasteClipboard(state);
  const NodeId ribCopy = state.selection[0];
  EXPECT_EQ(roleOf(state.document.root(), ribCopy), ChildRole::Add);
  EXPECT_TRUE(removesMaterial(state.document.root(), ribCopy));
  ASSERT_GE(state.log.size(), 2u);  // what it does, then where it landed
  const std::string& does = state.log[state.log.size() - 2].text;
  EXPECT_NE(does.find("inside a cutter"), std::string::npos) << does;
  EXPECT_NE(state.log.back().text.find("pasted"), std::string::npos) << state.log.back().text;
}

// An artist's test: a part dragged without a modifier onto a single part (not a group) came out
// with another role, and nothing said why. A countersink (it adds to a hole, so it takes
// material away) dropped onto the plate must cut to stay a hole: the sentence shown before the
// release, and the log after it, name the role change and what it keeps; undo gives the role
// back. A solid dropped onto a part of a hole cuts that part, and says so too.
TEST(Roles, ADropThatChangesARoleSaysSoBeforeTheRelease) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  state.selection = {hole};
  const NodeId countersink = addPrimitive(state, NodeKind::Cone);
  state.selection = {plate};
  const NodeId rib = addPrimitive(state, NodeKind::Box);
  ASSERT_EQ(roleOf(state.document.root(), countersink), ChildRole::Add);
  ASSERT_TRUE(removesMaterial(state.document.root(), countersink));
  ASSERT_TRUE(removesMaterial(state.document.root(), hole));

  const PlaceMode mode = dropMode(state, 0, countersink, plate);
  bool refused = true;
  const std::string sentence = placementSentence(state, plate, mode, countersink, &refused);
  EXPECT_FALSE(refused);
  dropNode(state, countersink, plate, mode);
  EXPECT_TRUE(removesMaterial(state.document.root(), countersink)) << sentence;
  EXPECT_EQ(roleOf(state.document.root(), countersink), ChildRole::Cut) << sentence;
  EXPECT_NE(sentence.find("its role changes from \"adds\" to \"cuts\", so that it still takes "
                          "material away"),
            std::string::npos)
      << sentence;
  ASSERT_FALSE(state.log.empty());
  EXPECT_NE(state.log.back().text.find("its role changes"), std::string::npos)
      << state.log.back().text;
  undo(state);
  EXPECT_EQ(roleOf(state.document.root(), countersink), ChildRole::Add);
  EXPECT_TRUE(removesMaterial(state.document.root(), countersink));

  // The rib (a solid) onto the hole, a part of the union of holes: it cuts that part (keeping
  // material from being cut there), said before the release.
  const std::string intoHole =
      placementSentence(state, hole, dropMode(state, 0, rib, hole), rib, &refused);
  EXPECT_FALSE(refused);
  EXPECT_NE(intoHole.find("its role changes from \"adds\" to \"cuts\", so that it still takes "
                          "no material away"),
            std::string::npos)
      << intoHole;
  // Moved within its own union (its role kept), nothing is said of roles.
  const std::string kept = placementSentence(state, plate, dropMode(state, 0, rib, plate), rib);
  EXPECT_EQ(kept.find("its role changes"), std::string::npos) << kept;
}

// Ctrl+V put the copy exactly on its original (the same name, nothing to see): a paste whose
// original is still there lands one grid step along +x, the next paste a step further; a cut
// part pasted lands where it was.
TEST(Roles, APasteLandsBesideItsOriginalAndACutOneWhereItWas) {
  EditorState state;
  const NodeId plate = addPrimitive(state, NodeKind::Box);
  const auto origin = [&](NodeId id) {
    return glm::dvec3(nodeWorldMatrix(state.document.root(), id) * glm::dvec4(0, 0, 0, 1));
  };
  const glm::dvec3 at = origin(plate);
  state.selection = {plate};
  copySelection(state);
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId first = state.selection[0];
  EXPECT_NEAR(glm::distance(origin(first), at + glm::dvec3(state.snap.step, 0, 0)), 0.0, 1e-9);
  const std::string name = findNode(state.document.root(), plate)->name;
  EXPECT_EQ(findNode(state.document.root(), first)->name, name + " copy");
  pasteClipboard(state);
  const NodeId second = state.selection[0];
  EXPECT_EQ(findNode(state.document.root(), second)->name, name + " copy 2");
  EXPECT_NEAR(glm::distance(origin(second), at + glm::dvec3(2 * state.snap.step, 0, 0)), 0.0, 1e-9);
  // Cut and pasted: moved, not shifted, even after a new part took the cut one's id (ids are
  // reused: the review's case); pasted again, a copy a step beside it.
  state.selection = {second};
  const glm::dvec3 secondAt = origin(second);
  cutSelection(state);
  EXPECT_FALSE(findNode(state.document.root(), second));
  EXPECT_NE(state.log.back().text.find("cut 1 part"), std::string::npos) << state.log.back().text;
  state.selection = {plate};
  const NodeId newcomer = addPrimitive(state, NodeKind::Sphere);
  EXPECT_EQ(newcomer, second) << "the test means a new part with the cut one's id";
  state.selection = {plate};
  pasteClipboard(state);
  const NodeId back = state.selection[0];
  EXPECT_NEAR(glm::distance(origin(back), secondAt), 0.0, 1e-9);
  pasteClipboard(state);
  EXPECT_NEAR(
      glm::distance(origin(state.selection[0]), secondAt + glm::dvec3(state.snap.step, 0, 0)), 0.0,
      1e-9);
  // Nothing selected: Ctrl+X does nothing and says nothing.
  state.selection.clear();
  const size_t lines = state.log.size();
  cutSelection(state);
  EXPECT_EQ(state.log.size(), lines);
}

// An artist cut a hole (a cutter in a difference beside other parts) and pasted with nothing
// selected: it came back cutting the whole scene (a new difference around the root), so it also
// drilled the ribs. A cut part goes back under its parent, in its place and role.
// A cut refused (the part is used by an instance) leaves the clipboard as it was: the next paste
// put a copy of the part it had refused to cut (an artist's test).
TEST(Roles, ARefusedCutLeavesTheClipboardAsItWas) {
  EditorState state;
  const NodeId kept = addPrimitive(state, NodeKind::Sphere);
  const NodeId used = addPrimitive(state, NodeKind::Box);
  state.selection = {kept};
  copySelection(state);
  state.selection = {used};
  instanceSelection(state);
  ASSERT_EQ(state.selection.size(), 1u);
  state.selection = {used};
  const size_t nodes = treeOrder(state.document.root()).size();
  cutSelection(state);
  EXPECT_TRUE(findNode(state.document.root(), used)) << "the cut was refused";
  ASSERT_EQ(state.clipboard.size(), 1u);
  EXPECT_EQ(state.clipboard[0].part->id, kept) << "the clipboard holds what it held";
  EXPECT_FALSE(state.clipboardFromCut);
  pasteClipboard(state);
  ASSERT_EQ(treeOrder(state.document.root()).size(), nodes + 1);
  EXPECT_EQ(findNode(state.document.root(), state.selection.at(0))->kind, NodeKind::Sphere);
}

TEST(Roles, ACutPartPastesBackUnderItsParentInItsRole) {
  EditorState state;
  const auto [plate, hole, second] = plateWithTwoHoles(state);
  state.placeMode = PlaceMode::Add;
  state.selection.clear();
  addPrimitive(state, NodeKind::Torus);  // beside the drilled plate, under the root
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodeId difference = where.parent->id;
  ASSERT_EQ(where.index, 1);
  const NodePtr before = state.document.root();
  // Cuts `id` and pastes with nothing selected; returns the part pasted (0: none).
  const auto cutAndPasteBack = [&](NodeId id) -> NodeId {
    state.selection = {id};
    cutSelection(state);
    if (findNode(state.document.root(), id)) return 0;
    state.selection.clear();
    pasteClipboard(state);
    return state.selection.size() == 1 ? state.selection[0] : 0;
  };
  const NodeId back = cutAndPasteBack(hole);
  ASSERT_TRUE(locateNode(state.document.root(), back, &where));
  EXPECT_EQ(where.parent->id, difference);
  EXPECT_EQ(where.index, 1);
  EXPECT_EQ(roleOf(state.document.root(), back), ChildRole::Cut);
  EXPECT_EQ(roleOf(state.document.root(), second), ChildRole::Cut);
  EXPECT_EQ(state.document.root()->kind, before->kind);
  EXPECT_EQ(state.document.root()->children.size(), before->children.size());
  EXPECT_NE(state.log.back().text.find("back in"), std::string::npos) << state.log.back().text;
  // The base cut (an empty base holds its place, so that the holes cut nothing) and pasted:
  // back first, the empty base gone, the holes cutting it again.
  const NodeId plateBack = cutAndPasteBack(plate);
  ASSERT_TRUE(locateNode(state.document.root(), plateBack, &where));
  EXPECT_EQ(where.parent->id, difference);
  EXPECT_EQ(where.index, 0);
  EXPECT_EQ(roleOf(state.document.root(), plateBack), ChildRole::Base);
  EXPECT_EQ(where.parent->children.size(), 3u) << "the empty base is gone";
  EXPECT_EQ(roleOf(state.document.root(), back), ChildRole::Cut);
  // Its parent gone meanwhile: placed as a new part is (onto the selection, in its role).
  state.selection = {back};
  cutSelection(state);
  state.document.remove(difference);
  state.selection.clear();
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  EXPECT_TRUE(findNode(state.document.root(), state.selection[0]));
}

// A hole copied and pasted with nothing selected cut the whole scene (an artist's re-test): the
// copy goes onto its original, as Ctrl+D's, and cuts what the original cuts.
TEST(Roles, ACopyPastedWithNothingSelectedGoesBesideItsOriginal) {
  EditorState state;
  const auto [plate, hole, second] = plateWithTwoHoles(state);
  state.placeMode = PlaceMode::Add;
  clearSelection(state);
  addPrimitive(state, NodeKind::Torus);  // beside the drilled plate, under the root
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodeId difference = where.parent->id;
  const NodeKind rootKind = state.document.root()->kind;
  state.selection = {hole};
  copySelection(state);
  clearSelection(state);
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId copy = state.selection[0];
  EXPECT_EQ(roleOf(state.document.root(), copy), ChildRole::Cut);
  EXPECT_TRUE(isInSubtree(state.document.root(), difference, copy));
  EXPECT_EQ(state.document.root()->kind, rootKind);
}

// Deleting a difference's base leaves an empty base holding its place; Delete on that did
// nothing visible and said nothing (an artist's re-test): it says why it stays.
TEST(Roles, DeletingAnEmptyBaseSaysWhyItStays) {
  EditorState state;
  const auto [plate, hole, second] = plateWithTwoHoles(state);
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodeId difference = where.parent->id;
  state.selection = {plate};
  deleteSelection(state);
  EXPECT_NE(state.log.back().text.find("deleted "), std::string::npos)
      << "said: " << state.log.back().text;
  const NodeId emptyBase = findNode(state.document.root(), difference)->children[0]->id;
  ASSERT_TRUE(findNode(state.document.root(), emptyBase)->children.empty());
  const NodePtr before = state.document.root();
  state.selection = {emptyBase};
  deleteSelection(state);
  EXPECT_TRUE(findNode(state.document.root(), emptyBase));
  EXPECT_EQ(state.document.root(), before) << "no edit, no undo step";
  EXPECT_NE(state.log.back().text.find("holds the base's place"), std::string::npos)
      << state.log.back().text;
}

// A re-test found that dropping a cutter onto the cutter below it moved it after that one and
// said only "cuts from ...": a drop within its own parent that keeps its role changes only its
// place, and says where it goes before and after the release.
TEST(Roles, ADropOntoASiblingSaysItOnlyChangesItsPlace) {
  EditorState state;
  const auto [plate, first, second] = plateWithTwoHoles(state);
  state.document.rename(first, "first hole");
  state.document.rename(second, "second hole");
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), first, &where));
  const NodeId difference = where.parent->id;
  ASSERT_EQ(where.index, 1);
  ASSERT_EQ(roleOf(state.document.root(), second), ChildRole::Cut);

  const std::string sentence = placementSentence(state, second, dropMode(state, 0, first), first);
  EXPECT_NE(sentence.find("moves after \"second hole\""), std::string::npos) << sentence;
  EXPECT_NE(sentence.find("role unchanged"), std::string::npos) << sentence;
  EXPECT_NE(sentence.find("cuts"), std::string::npos) << sentence;
  dropNode(state, first, second, dropMode(state, 0, first));
  ASSERT_TRUE(locateNode(state.document.root(), first, &where));
  EXPECT_EQ(where.parent->id, difference);
  EXPECT_EQ(where.index, 2);
  EXPECT_EQ(roleOf(state.document.root(), first), ChildRole::Cut);
  EXPECT_NE(state.log.back().text.find("moves after \"second hole\""), std::string::npos)
      << state.log.back().text;

  // Onto its own parent, where it already is the last child: it stays, and is said to.
  const std::string stays = placementSentence(state, difference, PlaceMode::Cut, first);
  EXPECT_NE(stays.find("stays where it is"), std::string::npos) << stays;
  // Onto the plate with "add": a new role, said as before (no "moves after").
  const std::string adds = placementSentence(state, plate, PlaceMode::Add, first);
  EXPECT_EQ(adds.find("role unchanged"), std::string::npos) << adds;
}

// An artist found no way to change an existing part's role but a drag with a modifier: the
// inspector's role and the outliner's Role menu (setRole) move the part onto its own parent with
// the mode picked; one undo step; the others keep theirs; refused, with a reason, for the root
// and a base.
TEST(Roles, ARolePickedWhereThePartIsChangesOnlyItsOwn) {
  EditorState state;
  const auto [plate, hole, difference] = addPlateWithHole(state);
  state.selection = {plate};
  const NodeId rib = addPrimitive(state, NodeKind::Box);
  ASSERT_EQ(roleOf(state.document.root(), rib), ChildRole::Add);
  const NodePtr before = state.document.root();
  setRole(state, rib, PlaceMode::Add);  // what it does already: nothing
  EXPECT_EQ(state.document.root(), before);
  setRole(state, rib, PlaceMode::Cut);
  EXPECT_EQ(roleOf(state.document.root(), rib), ChildRole::Cut);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  EXPECT_NE(state.log.back().text.find("cuts"), std::string::npos) << state.log.back().text;
  setRole(state, rib, PlaceMode::Intersect);
  EXPECT_EQ(roleOf(state.document.root(), rib), ChildRole::Intersect);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Cut);
  setRole(state, hole, PlaceMode::Add);
  EXPECT_EQ(roleOf(state.document.root(), hole), ChildRole::Add);
  EXPECT_FALSE(removesMaterial(state.document.root(), hole));
  undo(state);
  // The undo step is named for what the artist did (it said "undone: move": an artist's test).
  EXPECT_EQ(state.log.back().text, "undone: role");
  undo(state);
  undo(state);
  EXPECT_EQ(state.document.root(), before);  // three steps, one each
  // The difference's base (the union of the plate and the rib): refused, and said why.
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  const NodeId base = where.parent->children[0]->id;
  ASSERT_EQ(roleOf(state.document.root(), base), ChildRole::Base);
  setRole(state, base, PlaceMode::Cut);
  EXPECT_EQ(state.document.root(), before);
  EXPECT_NE(state.log.back().text.find("is the base of"), std::string::npos)
      << state.log.back().text;
  setRole(state, state.document.root()->id, PlaceMode::Cut);
  EXPECT_EQ(state.document.root(), before);
  EXPECT_NE(state.log.back().text.find("the root has no role"), std::string::npos);
  // The only child of an operation would land back where it was, doing what it did: refused
  // (an artist's "cuts" on the only bore of a union marked the scene changed and did nothing).
  state.selection = {rib};
  const NodeId group = addOperation(state, NodeKind::Union);
  NodeLocation inGroup;
  ASSERT_TRUE(locateNode(state.document.root(), group, &inGroup));
  const NodeId alone = addPrimitive(state, NodeKind::Sphere);
  if (NodeLocation at; locateNode(state.document.root(), alone, &at) && at.parent->id == group &&
                       at.parent->children.size() == 1) {
    const NodePtr withAlone = state.document.root();
    const uint64_t revision = state.document.revision();
    EXPECT_NE(roleChangeRefusal(state, alone, PlaceMode::Cut).find("holds nothing else"),
              std::string::npos)
        << roleChangeRefusal(state, alone, PlaceMode::Cut);
    setRole(state, alone, PlaceMode::Cut);
    EXPECT_EQ(state.document.root(), withAlone);
    EXPECT_EQ(state.document.revision(), revision) << "nothing changed, nothing to save";
  } else {
    ADD_FAILURE() << "the sphere did not land alone in the new union";
  }
}

// "cuts" picked for a part inside a shell: it cuts the shell's other parts there, stays inside
// the shell (an artist's opening left the shell, and a new difference cut the finished shell),
// and becomes the shell's opening where it has none (another artist's cut inside a shell made a
// closed pocket); says so before the click and in the log, and is undone as "role". A second
// cutter leaves the opening the first made.
TEST(Roles, ARolePickedInsideAShellCutsItsSiblingsThere) {
  EditorState state;
  const NodeId ball = addPrimitive(state, NodeKind::Sphere);
  state.selection = {ball};
  groupSelection(state, NodeKind::Shell);
  const Node* shellNode = parentOf(state, ball);
  ASSERT_NE(shellNode, nullptr);
  ASSERT_EQ(shellNode->kind, NodeKind::Shell);
  const NodeId shell = shellNode->id;
  state.selection = {ball};
  const NodeId bore = addPrimitive(state, NodeKind::Cylinder);
  ASSERT_TRUE(isInSubtree(state.document.root(), shell, bore));
  ASSERT_EQ(roleOf(state.document.root(), bore), ChildRole::Add);
  const NodePtr before = state.document.root();
  const std::string says = roleChangeSentence(state, bore, PlaceMode::Cut);
  EXPECT_NE(says.find("inside"), std::string::npos) << says;
  ASSERT_FALSE(findNode(before, ball)->name.empty());
  EXPECT_NE(says.find(findNode(before, ball)->name), std::string::npos) << says;
  EXPECT_NE(says.find("opens the shell's wall"), std::string::npos) << says;
  setRole(state, bore, PlaceMode::Cut);
  EXPECT_EQ(roleOf(state.document.root(), bore), ChildRole::Cut);
  EXPECT_EQ(roleOf(state.document.root(), ball), ChildRole::Base);
  EXPECT_TRUE(isInSubtree(state.document.root(), shell, bore));
  EXPECT_EQ(findNode(state.document.root(), shell)->children.size(), 1u);
  EXPECT_EQ(findNode(state.document.root(), shell)->opening, bore);
  EXPECT_EQ(shellOpening(findNode(state.document.root(), shell))->id, bore);
  EXPECT_NE(state.log.back().text.find(says), std::string::npos) << state.log.back().text;

  // A second cutter in the same shell: it cuts there too, and the opening stays the first's.
  state.selection = {ball};
  const NodeId vent = addPrimitive(state, NodeKind::Box);
  ASSERT_TRUE(isInSubtree(state.document.root(), shell, vent));
  const std::string second = roleChangeSentence(state, vent, PlaceMode::Cut);
  EXPECT_EQ(second.find("opens the shell's wall"), std::string::npos) << second;
  setRole(state, vent, PlaceMode::Cut);
  EXPECT_EQ(roleOf(state.document.root(), vent), ChildRole::Cut);
  EXPECT_EQ(findNode(state.document.root(), shell)->opening, bore);
  undo(state);
  undo(state);  // the box's addition
  undo(state);
  EXPECT_EQ(state.log.back().text, "undone: role");
  EXPECT_EQ(state.document.root(), before);
}

// A part added out of view (a copy one large step away from a part the view was zoomed onto)
// moves the view out to show it and the part that was in view, and says so; one added in view
// leaves the view as it is (an artist's part landed off screen without a word).
TEST(ImportAndPlace, APartAddedOutOfViewIsShownWithWhatWasInView) {
  EditorState state;
  const NodeId first = addPrimitive(state, NodeKind::Box);
  const ViewRect rect{0.0, 0.0, 800.0, 600.0};
  Viewport view;
  view.camera.frame(selectionBounds(state.document.root(), {first}), 800.0 / 600.0);
  const Camera zoomed = view.camera;
  ASSERT_TRUE(state.revealSelection);
  EXPECT_FALSE(view.revealSelection(state, rect));
  EXPECT_FALSE(state.revealSelection);
  EXPECT_EQ(view.camera.target, zoomed.target);
  EXPECT_EQ(view.camera.distance, zoomed.distance);

  state.snapFollowsGrid = false;
  state.snap.step = 400.0;
  state.selection = {first};
  duplicateSelection(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId copy = state.selection[0];
  ASSERT_TRUE(state.revealSelection);
  EXPECT_TRUE(view.revealSelection(state, rect));
  EXPECT_NE(state.log.back().text.find("out of view"), std::string::npos) << state.log.back().text;
  EXPECT_GT(view.camera.distance, zoomed.distance);
  for (NodeId shown : {copy, first}) {
    state.selection = {shown};
    EXPECT_FALSE(view.revealSelection(state, rect)) << "in view now: " << shown;
  }
  // Not the whole scene's framing where a far part would be left out of it: both, no more.
  EXPECT_LT(view.camera.distance, 4.0 * 400.0);
}

// A mirror of a part far from its parent's origin has its image as far on the other side: the
// view, framed on the part, moves out to show the image too.
TEST(ImportAndPlace, AMirrorsImageOutOfViewIsShown) {
  EditorState state;
  Transform far;
  far.translate = glm::dvec3(300.0, 0.0, 0.0);
  const NodeId rib = addPartAt(state, NodeKind::Box, far);
  const ViewRect rect{0.0, 0.0, 800.0, 600.0};
  Viewport view;
  view.camera.frame(selectionBounds(state.document.root(), {rib}), 800.0 / 600.0);
  state.selection = {rib};
  groupSelection(state, NodeKind::Mirror);
  const Bounds both = selectionBounds(state.document.root(), state.selection);
  ASSERT_LT(both.min.x, -250.0) << "the image lies across the parent's origin";
  ASSERT_TRUE(state.revealSelection);
  EXPECT_TRUE(view.revealSelection(state, rect));
  EXPECT_FALSE(view.revealSelection(state, rect)) << "both in view now";
}

// A selected mirror (or a part inside it) shows its plane, a circular array its axis, through
// the pattern's centre in the world and as wide as the pattern; nothing else shows a guide.
TEST(ImportAndPlace, AMirrorsPlaneAndACircularArraysAxisAreShown) {
  EditorState state;
  Transform far;
  far.translate = glm::dvec3(30.0, 0.0, 0.0);
  const NodeId rib = addPartAt(state, NodeKind::Box, far);
  EXPECT_TRUE(patternGuides(state).empty()) << "a part in no pattern";
  state.selection = {rib};
  groupSelection(state, NodeKind::Mirror);
  const NodeId mirror = state.selection.at(0);
  std::vector<PatternGuide> guides = patternGuides(state);
  ASSERT_EQ(guides.size(), 1u);
  EXPECT_TRUE(guides[0].plane);
  EXPECT_EQ(guides[0].node, mirror);
  EXPECT_NEAR(guides[0].point.x, 0.0, 1e-9) << "the plane x = 0 of the mirror's frame";
  EXPECT_NEAR(guides[0].u.x, 0.0, 1e-9);
  EXPECT_NEAR(guides[0].v.x, 0.0, 1e-9);
  EXPECT_GT(glm::length(guides[0].u), 30.0) << "as wide as the pattern (about 70 mm)";
  EXPECT_NE(guides[0].label.find("across x"), std::string::npos) << guides[0].label;
  state.selection = {rib};  // a part inside it: the same guide
  ASSERT_EQ(patternGuides(state).size(), 1u);
  EXPECT_EQ(patternGuides(state)[0].node, mirror);

  state.selection = {mirror};
  setSelectionOperation(state, NodeKind::CircularArray);
  guides = patternGuides(state);
  ASSERT_EQ(guides.size(), 1u);
  EXPECT_FALSE(guides[0].plane);
  EXPECT_NEAR(glm::length(guides[0].u - glm::dvec3(0.0, 0.0, glm::length(guides[0].u))), 0.0, 1e-9)
      << "along z";
  EXPECT_TRUE(state.revealSelection) << "its copies shown where they lie";
  undo(state);
  undo(state);
}

// An error is settled by a later success on its topic: a refused 100000 cells does not stay red
// once 512 is applied (an artist read it as the 512's failure).
TEST(EditorLog, ALaterSuccessOnTheSameTopicSettlesItsError) {
  EditorState state;
  addPrimitive(state, NodeKind::Box);
  setResolution(state, 100000);
  ASSERT_EQ(state.log.back().level, LogLevel::Error);
  EXPECT_FALSE(state.log.back().dismissed);
  EXPECT_EQ(state.log.back().topic, "resolution");
  guarded(state, [] { throw Error("another refusal"); });
  setResolution(state, 512);
  EXPECT_EQ(state.document.scene().settings.resolution, 512);
  size_t open = 0;
  for (const LogLine& line : state.log) open += line.level == LogLevel::Error && !line.dismissed;
  EXPECT_EQ(open, 1u) << "the other error stays until read";
}

// Ctrl+D: the copy does what its original does and sits one move-snap step along world +x
// from it (under a turned, scaled parent too), so that it is seen; one undo step for all copies.
TEST(Roles, DuplicatesKeepTheirRoleAndSitOneGridStepAlongX) {
  EditorState state;
  const NodeId plate = addPrimitive(state, NodeKind::Box);
  state.placeMode = PlaceMode::Cut;
  const NodeId hole = addPrimitive(state, NodeKind::Cylinder);
  NodeLocation where;
  ASSERT_TRUE(locateNode(state.document.root(), hole, &where));
  Transform turned;
  turned.rotateDegrees = glm::dvec3(0.0, 0.0, 90.0);
  turned.scale = glm::dvec3(2.0);
  ASSERT_TRUE(guarded(state, [&] { state.document.setTransform(where.parent->id, turned); }));
  state.snap.step = 0.5;
  const Bounds plateBefore = selectionBounds(state.document.root(), {plate});
  const Bounds holeBefore = selectionBounds(state.document.root(), {hole});
  state.selection = {plate, hole};
  duplicateSelection(state);
  ASSERT_EQ(state.selection.size(), 2u);
  const NodeId plateCopy = state.selection[0], holeCopy = state.selection[1];
  const NodePtr& root = state.document.root();
  EXPECT_EQ(roleOf(root, holeCopy), ChildRole::Cut);
  // The base's copy unites with it in a union in the base's place: both stay material.
  ASSERT_TRUE(locateNode(root, plateCopy, &where));
  EXPECT_EQ(roleOf(root, where.parent->id), ChildRole::Base);
  EXPECT_FALSE(removesMaterial(root, plate));
  EXPECT_FALSE(removesMaterial(root, plateCopy));
  const glm::dvec3 step(0.5, 0.0, 0.0);
  EXPECT_NEAR(
      glm::distance(selectionBounds(root, {plateCopy}).center(), plateBefore.center() + step), 0.0,
      1e-9);
  EXPECT_NEAR(glm::distance(selectionBounds(root, {holeCopy}).center(), holeBefore.center() + step),
              0.0, 1e-9);
  EXPECT_NEAR(glm::distance(selectionBounds(root, {hole}).center(), holeBefore.center()), 0.0,
              1e-9);
  EXPECT_NE(state.log.back().text.find("one grid step"), std::string::npos)
      << state.log.back().text;
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), plateCopy));
  EXPECT_FALSE(findNode(state.document.root(), holeCopy));
}

// Ctrl+D pressed twice on the same original (the selection put back on it): the second copy
// goes one step beyond the first instead of onto it (two parts that look like one), and says so.
TEST(Roles, DuplicatingTheOriginalAgainGoesBesideTheFirstCopy) {
  EditorState state;
  const NodeId a = addPrimitive(state, NodeKind::Sphere);
  const NodeId b = addPrimitive(state, NodeKind::Sphere);  // beside it, elsewhere
  ASSERT_NE(b, 0u);
  state.snap.step = 2.0;
  const glm::dvec3 at = findNode(state.document.root(), a)->transform.translate;
  state.selection = {a};
  duplicateSelection(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId first = state.selection[0];
  EXPECT_NEAR(glm::distance(findNode(state.document.root(), first)->transform.translate,
                            at + glm::dvec3(2, 0, 0)),
              0.0, 1e-9);
  state.selection = {a};
  duplicateSelection(state);
  const NodeId second = state.selection[0];
  EXPECT_NEAR(glm::distance(findNode(state.document.root(), second)->transform.translate,
                            at + glm::dvec3(4, 0, 0)),
              0.0, 1e-9);
  EXPECT_NE(state.log.back().text.find("2 grid steps"), std::string::npos) << state.log.back().text;
  // Listed as the row sits: the original, the first copy, the second (it came between them).
  NodeLocation original, firstAt, secondAt;
  ASSERT_TRUE(locateNode(state.document.root(), a, &original));
  ASSERT_TRUE(locateNode(state.document.root(), first, &firstAt));
  ASSERT_TRUE(locateNode(state.document.root(), second, &secondAt));
  EXPECT_EQ(firstAt.parent, secondAt.parent);
  EXPECT_EQ(firstAt.index, original.index + 1);
  EXPECT_EQ(secondAt.index, firstAt.index + 1);
  EXPECT_EQ(roleOf(state.document.root(), second), roleOf(state.document.root(), a));
  undo(state);
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), first));
  EXPECT_FALSE(findNode(state.document.root(), second));
  EXPECT_TRUE(findNode(state.document.root(), b));
}

// A cutter copied twice with Ctrl+D: both copies cut, listed after the first copy in the row's
// order, the plate still the base; one undo step each.
TEST(Roles, ACutterCopiedTwiceKeepsEveryRoleAndTheRowsOrder) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  ASSERT_NE(group, 0u);
  state.snap.step = 1.0;
  state.selection = {hole};
  duplicateSelection(state);
  const NodeId first = state.selection.at(0);
  state.selection = {hole};
  duplicateSelection(state);
  const NodeId second = state.selection.at(0);
  const NodePtr& root = state.document.root();
  const NodePtr holder = findNode(root, group);
  ASSERT_TRUE(holder);
  std::vector<NodeId> order;
  for (const NodePtr& c : holder->children) order.push_back(c->id);
  EXPECT_EQ(order, (std::vector<NodeId>{plate, hole, first, second}));
  EXPECT_EQ(roleOf(root, plate), ChildRole::Base);
  for (NodeId cutter : {hole, first, second}) EXPECT_EQ(roleOf(root, cutter), ChildRole::Cut);
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), second));
  EXPECT_TRUE(findNode(state.document.root(), first));
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), first));
}

// A part that adds to a cutter (a countersink in a union of holes) takes material away: copied
// and pasted onto the plate, or dragged onto it in the outliner, it still does (it became a peg
// where it was a hole: an artist's test); grouped with the plate (Ctrl+G) it is refused.
TEST(Roles, APartOfACutterPastedOrDroppedOnTheBaseStillCuts) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  selectNode(state, hole);
  state.placeMode = PlaceMode::Add;
  const NodeId countersink = addPrimitive(state, NodeKind::Cone);  // adds to the hole: a union
  const NodePtr& root = state.document.root();
  ASSERT_EQ(roleOf(root, countersink), ChildRole::Add);
  ASSERT_TRUE(removesMaterial(root, countersink));

  state.selection = {countersink};
  copySelection(state);
  state.selection = {plate};
  pasteClipboard(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId pasted = state.selection[0];
  EXPECT_NE(pasted, countersink);
  EXPECT_TRUE(removesMaterial(state.document.root(), pasted)) << "the pasted copy fills";
  undo(state);
  EXPECT_FALSE(findNode(state.document.root(), pasted));

  dropNodes(state, countersink, plate, 0);
  EXPECT_TRUE(removesMaterial(state.document.root(), countersink)) << "the dropped part fills";
  undo(state);

  state.selection = {plate, countersink};
  const NodePtr before = state.document.root();
  groupSelection(state, groupKindKeepingRoles(state));
  EXPECT_EQ(state.document.root(), before) << "grouped into the plate, the countersink would fill";
  EXPECT_NE(state.log.back().text.find("would no longer do what it did"), std::string::npos)
      << state.log.back().text;
}

// Grouping parts one of which an instance repeats leaves that part's own transform alone (the
// group's origin stays its parent's): centring the group moved the cross bore back by as much,
// and the instance that repeats it with its transform took its y-bore elsewhere (an artist's
// re-test).
TEST(Roles, AGroupAroundAPartAnInstanceRepeatsLeavesItsTransform) {
  EditorState state;
  ASSERT_TRUE(openDocument(state, std::string(STRATA_ASSETS) + "/scenes/demo.strata.json"));
  const auto named = [&](const std::string& name) {
    for (NodeId id : treeOrder(state.document.root()))
      if (findNode(state.document.root(), id)->name == name) return id;
    return NodeId(0);
  };
  const NodeId holes = named("bolt holes"), bore = named("cross bore");
  ASSERT_NE(holes, 0u);
  ASSERT_NE(bore, 0u);
  ASSERT_TRUE(instanceRepeating(state.document.root(), bore));
  const Transform before = findNode(state.document.root(), bore)->transform;
  const glm::dmat4 world = nodeWorldMatrix(state.document.root(), bore);
  state.selection = {holes, bore};
  groupSelection(state, NodeKind::Union);
  ASSERT_EQ(state.selection.size(), 1u);
  EXPECT_NE(state.selection[0], holes) << "grouped";
  EXPECT_EQ(findNode(state.document.root(), bore)->transform, before);
  EXPECT_EQ(nodeWorldMatrix(state.document.root(), bore), world);
  undo(state);
}

// A group and a part inside it selected together: what acts on the selection acts on the
// group once, the part moving with it (an artist's test: Ctrl+D copied the part twice, the
// inspector moved it twice, the gizmo turned only the part).
TEST(Roles, AGroupAndAPartInsideItActAsTheGroup) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  ASSERT_NE(group, 0u);
  ASSERT_NE(group, hole);
  state.selection = {group, hole};
  const NodePtr& before = state.document.root();
  EXPECT_EQ(selectedHolder(before, state.selection, hole), group);
  EXPECT_EQ(selectedHolder(before, {plate, hole}, hole), hole);
  EXPECT_EQ(outermostSelected(before, state.selection), std::vector<NodeId>{group});
  const size_t nodes = treeOrder(before).size();
  const size_t inside = treeOrder(findNode(before, group)).size();
  duplicateSelection(state);
  ASSERT_EQ(state.selection.size(), 1u);  // one copy: the group's, with the part in it
  EXPECT_EQ(treeOrder(state.document.root()).size(), nodes + inside);
  undo(state);
  EXPECT_EQ(treeOrder(state.document.root()).size(), nodes);
}

// Shift+click selects the rows shown between the two ends: not the parts of an operation
// collapsed between them (an artist's test: "59 selected" with 7 rows lit).
TEST(Roles, ARangeSelectsTheRowsShownNotACollapsedGroupsParts) {
  EditorState state;
  const auto [first, hole, group] = addPlateWithHole(state);
  const NodeId last = addPrimitive(state, NodeKind::Sphere);
  // Shown: the root, the group (collapsed: its parts hidden), the last part.
  const std::vector<NodeId> rows = {state.document.root()->id, group, last};
  selectNode(state, group);
  selectRange(state, last, rows);
  EXPECT_EQ(state.selection, (std::vector<NodeId>{group, last}));
  EXPECT_FALSE(isSelected(state, first));
  EXPECT_FALSE(isSelected(state, hole));
  // Without the rows (or an end not among them): the tree's order, the parts between included.
  selectNode(state, group);
  selectRange(state, last);
  EXPECT_TRUE(isSelected(state, hole));
}

// Several selected rows dragged onto a part move together, each keeping what it does, as one
// undo step (an artist's test: the press on one row dropped the others from the selection and
// only it moved); a drop refused for one moves none.
TEST(Roles, SeveralSelectedRowsDroppedMoveTogetherAsOneStep) {
  EditorState state;
  const auto [plate, hole, group] = addPlateWithHole(state);
  const NodeId a = addPrimitive(state, NodeKind::Sphere);
  clearSelection(state);
  const NodeId b = addPrimitive(state, NodeKind::Torus);
  const NodePtr before = state.document.root();
  state.selection = {a, b};
  dropNodes(state, b, plate, 0);
  const NodePtr& root = state.document.root();
  EXPECT_TRUE(isInSubtree(root, group, a));
  EXPECT_TRUE(isInSubtree(root, group, b));
  EXPECT_FALSE(removesMaterial(root, a));
  EXPECT_FALSE(removesMaterial(root, b));
  undo(state);
  EXPECT_EQ(state.document.root(), before);
  // The group and a part beside it dropped onto the group's own part: refused whole.
  state.selection = {group, a};
  dropNodes(state, a, hole, 0);
  EXPECT_EQ(state.document.root(), before);
  EXPECT_EQ(state.log.back().level, LogLevel::Error);
  // The group and a part inside it, the part's row dragged: the group moves (as the gizmo
  // moves it), the part stays in it.
  state.selection = {group, hole};
  dropNodes(state, hole, b, 0);
  EXPECT_TRUE(isInSubtree(state.document.root(), group, hole));
  undo(state);
  EXPECT_EQ(state.document.root(), before);
}

TEST(Instances, InstanceFollowsItsOriginalAndIsOneUndoStep) {
  EditorState state;
  NodeId box = addPrimitive(state, NodeKind::Box);
  NodeId ball = addPrimitive(state, NodeKind::Sphere);  // beside the box
  state.selection = {box};
  instanceSelection(state);
  ASSERT_EQ(state.selection.size(), 1u);
  const NodeId instance = state.selection[0];
  NodePtr node = findNode(state.document.root(), instance);
  ASSERT_TRUE(node);
  EXPECT_EQ(node->kind, NodeKind::Instance);
  EXPECT_EQ(node->instanceOf, box);
  // Right after the original in its parent.
  const auto& siblings = state.document.root()->children;
  ASSERT_EQ(siblings.size(), 3u);
  EXPECT_EQ(siblings[0]->id, box);
  EXPECT_EQ(siblings[1]->id, instance);
  EXPECT_EQ(siblings[2]->id, ball);
  // It shows the original, and follows its edits; moving it moves only the instance.
  EXPECT_EQ(selectionBounds(state.document.root(), {instance}).size(),
            selectionBounds(state.document.root(), {box}).size());
  ASSERT_TRUE(guarded(state, [&] {
    PrimitiveParams p;
    p.size = glm::dvec3(3.0, 1.0, 1.0);
    state.document.setParams(box, p);
    Transform t;
    t.translate = glm::dvec3(0.0, 5.0, 0.0);
    state.document.setTransform(instance, t);
  }));
  const Bounds moved = selectionBounds(state.document.root(), {instance});
  EXPECT_NEAR(moved.size().x, 3.0, 1e-9);
  EXPECT_NEAR(moved.center().y, 5.0, 1e-9);
  EXPECT_NEAR(selectionBounds(state.document.root(), {box}).center().y, 0.0, 1e-9);
  // The original cannot be deleted while the instance uses it; undo removes the instance.
  state.selection = {box};
  deleteSelection(state);
  EXPECT_TRUE(findNode(state.document.root(), box));
  undo(state);  // the move
  undo(state);  // the size
  undo(state);  // the instance
  EXPECT_FALSE(findNode(state.document.root(), instance));
  EXPECT_TRUE(findNode(state.document.root(), box));
}

TEST(Instances, TheRootCannotBeInstanced) {
  EditorState state;
  addPrimitive(state, NodeKind::Box);
  state.selection = {state.document.root()->id};
  const uint64_t revision = state.document.revision();
  instanceSelection(state);
  EXPECT_EQ(state.document.revision(), revision);
  ASSERT_FALSE(state.log.empty());
  EXPECT_NE(state.log.back().text.find("root cannot be instanced"), std::string::npos);
}

}  // namespace
}  // namespace strata::ui

namespace strata::ui {
namespace {

// New parts are sized from the scene (a quarter of its largest extent) or, in an empty scene,
// from the view (a quarter of what it shows), and the log says which; the move snap follows the
// ground grid.
TEST(ScaleAwareDefaults, NewPartsAreSizedFromTheViewOrTheSceneAndSaySo) {
  EditorState state;
  state.viewExtent = 400.0;  // an empty scene seen 400 mm high
  const NodeId first = addPrimitive(state, NodeKind::Box);
  const Bounds a = selectionBounds(state.document.root(), {first});
  EXPECT_NEAR(a.size().x, 100.0, 1e-9);
  // The first part stands on the ground at the origin (it was centred there, half below it).
  EXPECT_NEAR(a.min.z, 0.0, 1e-9);
  EXPECT_NEAR(a.center().x, 0.0, 1e-9);
  EXPECT_NEAR(a.center().y, 0.0, 1e-9);
  EXPECT_NE(state.log.back().text.find("a quarter of the view"), std::string::npos)
      << state.log.back().text;
  const NodeId second = addPrimitive(state, NodeKind::Sphere);
  const Bounds b = selectionBounds(state.document.root(), {second});
  // A quarter of the 100 mm scene, rounded (20), times the default sphere.
  const double defaultSize =
      primitiveLocalBounds(NodeKind::Sphere, primitiveInfo(NodeKind::Sphere)->defaults).size().x;
  EXPECT_NEAR(b.size().x, niceLength(25.0) * defaultSize, 1e-6);
  EXPECT_NE(state.log.back().text.find("a quarter of the scene"), std::string::npos)
      << state.log.back().text;
  // It adds: it rests on the box's top, over its middle (centred there, it sat half sunk).
  EXPECT_NEAR(b.min.z, a.max.z, 1e-9);
  EXPECT_NEAR(b.center().x, a.center().x, 1e-9);
  const Bounds scene = sceneBounds(state.document.root());
  EXPECT_NEAR(scene.size().z, 120.0, 1e-6);
  EXPECT_EQ(groundGridStep(scene), niceLength(120.0 / 8.0));  // its largest extent / 8, rounded
  // Zoomed in on a detail (the view 40 mm high), nothing selected: a quarter of the view, not of
  // the scene, which hid the detail (an artist's test).
  state.viewExtent = 40.0;
  clearSelection(state);
  const NodeId third = addPrimitive(state, NodeKind::Box);
  EXPECT_NEAR(selectionBounds(state.document.root(), {third}).size().x, niceLength(10.0), 1e-9);
  EXPECT_NE(state.log.back().text.find("a quarter of the view"), std::string::npos)
      << state.log.back().text;
}

}  // namespace
}  // namespace strata::ui
