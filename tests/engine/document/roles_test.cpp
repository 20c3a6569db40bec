// Roles (engine/document/roles.h): what each child does, and placing and moving parts so that
// no existing part changes what it does. The rules on a small tree, then every (part, target,
// mode) of every bundled scene checked on the tree and, where a direction is known, on the
// evaluated volume.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "engine/document/commands.h"
#include "engine/document/document.h"
#include "engine/document/measurement.h"
#include "engine/document/roles.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"
#include "tests/support/part_directions.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

// root(1, union) { a(2, box), g(3, difference) { b(4, sphere), c(5, cylinder) }, d(6, torus) }
NodePtr sampleTree() {
  NodePtr g = makeOperationNode(
      NodeKind::Difference, 3,
      {makePrimitiveNode(NodeKind::Sphere, 4), makePrimitiveNode(NodeKind::Cylinder, 5)});
  return makeOperationNode(
      NodeKind::Union, 1,
      {makePrimitiveNode(NodeKind::Box, 2), g, makePrimitiveNode(NodeKind::Torus, 6)});
}

std::vector<NodeId> childIds(const NodePtr& node) {
  std::vector<NodeId> ids;
  for (const auto& c : node->children) ids.push_back(c->id);
  return ids;
}

ChildRole roleFor(PlaceMode mode) {
  return mode == PlaceMode::Cut         ? ChildRole::Cut
         : mode == PlaceMode::Intersect ? ChildRole::Intersect
                                        : ChildRole::Add;
}

const PlaceMode kModes[] = {PlaceMode::Add, PlaceMode::Cut, PlaceMode::Intersect};

TEST(Roles, ChildRolesFollowTheParentsBoolean) {
  NodePtr root = sampleTree();
  EXPECT_EQ(roleOf(root, 1), ChildRole::Root);
  EXPECT_EQ(roleOf(root, 2), ChildRole::Add);
  EXPECT_EQ(roleOf(root, 4), ChildRole::Base);
  EXPECT_EQ(roleOf(root, 5), ChildRole::Cut);
  EXPECT_TRUE(removesMaterial(root, 5));
  EXPECT_FALSE(removesMaterial(root, 4));
  NodePtr inter = setOperationKind(root, 3, NodeKind::Intersection);
  EXPECT_EQ(roleOf(inter, 4), ChildRole::Intersect);
  EXPECT_EQ(roleOf(inter, 5), ChildRole::Intersect);
  EXPECT_THROW(roleOf(root, 99), Error);
}

TEST(Roles, TheThreePlacementRules) {
  NodePtr root = sampleTree();
  NodePtr part = makePrimitiveNode(NodeKind::Cone, 7);
  // 1. Into an operation of the mode's Boolean: last child.
  PlacePlan into = planPlacement(root, 3, PlaceMode::Cut);
  EXPECT_EQ(childIds(findNode(placePart(root, into, part, 8), 3)), (std::vector<NodeId>{4, 5, 7}));
  EXPECT_EQ(into.sentence, "cuts from \"difference 3\"");
  // 2. Beside a target playing the mode's role.
  PlacePlan beside = planPlacement(root, 5, PlaceMode::Cut);
  EXPECT_EQ(childIds(findNode(placePart(root, beside, part, 8), 3)),
            (std::vector<NodeId>{4, 5, 7}));
  PlacePlan besideAdd = planPlacement(root, 2, PlaceMode::Add);
  EXPECT_EQ(childIds(placePart(root, besideAdd, part, 8)), (std::vector<NodeId>{2, 7, 3, 6}));
  // 3. Otherwise wrapped: adding to the base unites it with the part in the base's place.
  PlacePlan wrap = planPlacement(root, 4, PlaceMode::Add);
  NodePtr wrapped = placePart(root, wrap, part, 8);
  EXPECT_EQ(childIds(findNode(wrapped, 3)), (std::vector<NodeId>{8, 5}));
  EXPECT_EQ(findNode(wrapped, 8)->kind, NodeKind::Union);
  EXPECT_EQ(childIds(findNode(wrapped, 8)), (std::vector<NodeId>{4, 7}));
  EXPECT_NE(wrap.sentence.find("new union"), std::string::npos);
  // Cutting the root wraps the whole scene in a difference.
  NodePtr cutRoot = placePart(root, planPlacement(root, 1, PlaceMode::Cut), part, 8);
  EXPECT_EQ(cutRoot->id, 8u);
  EXPECT_EQ(cutRoot->kind, NodeKind::Difference);
  EXPECT_EQ(childIds(cutRoot), (std::vector<NodeId>{1, 7}));
  // An empty operation takes the part as its first child, whatever the mode.
  NodePtr empty = insertChild(root, 1, -1, makeOperationNode(NodeKind::Difference, 9, {}));
  PlacePlan fill = planPlacement(empty, 9, PlaceMode::Cut);
  EXPECT_EQ(childIds(findNode(placePart(empty, fill, part, 10), 9)), (std::vector<NodeId>{7}));
  EXPECT_EQ(fill.sentence, "becomes the base of \"difference 9\"");
}

// A part added onto a modifier's or a pattern's row goes into it, as into a folder (an artist's
// test saw it land beside the shell); a cutter cuts the finished shell; a duplicate of the shell
// lands beside it.
TEST(Roles, APartAddedOntoAModifierOrAPatternJoinsWhatItChangesOrRepeats) {
  for (const NodeKind kind : {NodeKind::Shell, NodeKind::Offset, NodeKind::Array,
                              NodeKind::CircularArray, NodeKind::Mirror}) {
    SCOPED_TRACE(kindName(kind));
    // root(1, union) { box(2), m(3, kind) { sphere(4) } }
    const NodePtr root =
        makeOperationNode(NodeKind::Union, 1,
                          {makePrimitiveNode(NodeKind::Box, 2),
                           makeOperationNode(kind, 3, {makePrimitiveNode(NodeKind::Sphere, 4)})});
    const NodePtr part = makePrimitiveNode(NodeKind::Cone, 7);
    const PlacePlan into = planPlacement(root, 3, PlaceMode::Add);
    const NodePtr placed = placePart(root, into, part, 8);
    EXPECT_EQ(childIds(findNode(placed, 3)), (std::vector<NodeId>{4, 7}));
    EXPECT_EQ(childIds(placed), (std::vector<NodeId>{2, 3}));
    EXPECT_EQ(into.sentence, "joins what \"" + findNode(root, 3)->name + "\" " +
                                 (patternOf(kind) != Pattern::None ? "repeats" : "changes") +
                                 " (it becomes one of its parts)");
    EXPECT_FALSE(into.removesMaterial);
    // Beside it where the caller asks (what a duplicate of it does).
    const PlacePlan beside = planPlacement(root, 3, PlaceMode::Add, IntoUniting::No);
    EXPECT_EQ(childIds(placePart(root, beside, part, 8)), (std::vector<NodeId>{2, 3, 7}));
    NodeId copy = 0;
    const NodePtr duplicated = duplicateNode(root, 3, 8, &copy);
    EXPECT_EQ(childIds(duplicated), (std::vector<NodeId>{2, 3, copy}));
    // A cutter cuts the finished result: a new difference takes its place.
    const NodePtr cut = placePart(root, planPlacement(root, 3, PlaceMode::Cut), part, 8);
    EXPECT_EQ(childIds(cut), (std::vector<NodeId>{2, 8}));
    EXPECT_EQ(childIds(findNode(cut, 8)), (std::vector<NodeId>{3, 7}));
    // A row dragged onto it moves into it, keeping its place in the world.
    const NodePtr moved = movePart(root, 2, 3, PlaceMode::Add, 9);
    EXPECT_EQ(childIds(findNode(moved, 3)), (std::vector<NodeId>{4, 2}));
    // Inside a cutter it takes material away, and the sentence says so.
    const NodePtr holes = makeOperationNode(
        NodeKind::Difference, 1, {makePrimitiveNode(NodeKind::Box, 2), findNode(root, 3)});
    const PlacePlan hole = planPlacement(holes, 3, PlaceMode::Add);
    EXPECT_TRUE(hole.removesMaterial);
    EXPECT_NE(hole.sentence.find("inside a cutter"), std::string::npos);
  }
}

// A drop's tooltip says what the moved part stops doing where it was: a cutter dragged away
// took its hole out of the part it cut, a solid dragged out of a mirror its image, and the
// tooltip named only where they went (an artist's test).
TEST(Roles, AMovedPartSaysWhatItNoLongerDoesWhereItWas) {
  const NodePtr root = sampleTree();
  const auto name = [&](NodeId id) { return "\"" + findNode(root, id)->name + "\""; };
  // The cutter onto the box: it no longer cuts the sphere.
  EXPECT_EQ(leavesNote(root, movePart(root, 5, 2, PlaceMode::Cut, 10), 5),
            "; it no longer cuts " + name(4));
  // The base away: its difference keeps cutters over an empty base.
  EXPECT_EQ(leavesNote(root, movePart(root, 4, 6, PlaceMode::Add, 10), 4),
            "; it is no longer the base of " + name(3) + ", whose cutters then cut nothing");
  // Beside a sibling, or wrapped with one, it stays where it acted: nothing to say.
  EXPECT_EQ(leavesNote(root, movePart(root, 2, 6, PlaceMode::Add, 10), 2), "");
  EXPECT_EQ(leavesNote(root, movePart(root, 5, 4, PlaceMode::Add, 10), 5), "");
  // Out of a mirror: its image goes, and the mirror is left empty.
  const NodePtr mirrored = insertChild(
      root, 1, -1, makeOperationNode(NodeKind::Mirror, 7, {makePrimitiveNode(NodeKind::Cone, 8)}));
  EXPECT_EQ(leavesNote(mirrored, movePart(mirrored, 8, 2, PlaceMode::Add, 10), 8),
            "; it no longer adds to \"" + findNode(mirrored, 7)->name +
                "\", nor is repeated by it; \"" + findNode(mirrored, 7)->name + "\" is left empty");
  // Wrapped with the base it cut, it still cuts it: nothing to say.
  EXPECT_EQ(leavesNote(root, movePart(root, 5, 4, PlaceMode::Cut, 10), 5), "");
  // Into the base it cut (the bore of a plate dropped into the plate's body, a union): it no
  // longer cuts it, though it stays inside its old parent.
  const NodePtr plate = makeOperationNode(
      NodeKind::Difference, 1,
      {makeOperationNode(NodeKind::Union, 2, {makePrimitiveNode(NodeKind::Box, 3)}),
       makePrimitiveNode(NodeKind::Cylinder, 4)});
  EXPECT_EQ(leavesNote(plate, movePart(plate, 4, 2, PlaceMode::Add, 10), 4),
            "; it no longer cuts \"" + findNode(plate, 2)->name + "\"");
  // The root stays the root.
  EXPECT_EQ(leavesNote(root, root, 1), "");
}

// Switching an operation's Boolean changes its children's roles: said before the click.
TEST(Roles, TheSentenceOfAKindChangeNamesEveryChildWhoseRoleChanges) {
  const NodePtr body = makeOperationNode(
      NodeKind::Union, 1,
      {makePrimitiveNode(NodeKind::Box, 2), makePrimitiveNode(NodeKind::Cylinder, 3),
       makePrimitiveNode(NodeKind::Sphere, 4)});
  EXPECT_EQ(roleChangesOfKind(*body, NodeKind::Difference),
            "\"box 2\" becomes the base; \"cylinder 3\" and \"sphere 4\" will cut");
  EXPECT_EQ(roleChangesOfKind(*body, NodeKind::Intersection),
            "\"box 2\", \"cylinder 3\" and \"sphere 4\" will intersect");
  EXPECT_EQ(roleChangesOfKind(*body, NodeKind::Union), "");
}

TEST(Roles, RemovingABaseWithCuttersLeavesAnEmptyBase) {
  NodePtr root = sampleTree();
  NodePtr removed = removeNode(root, 4);
  ASSERT_EQ(findNode(removed, 3)->children.size(), 2u);
  const NodePtr& base = findNode(removed, 3)->children[0];
  EXPECT_EQ(base->kind, NodeKind::Union);
  EXPECT_TRUE(base->children.empty());
  EXPECT_EQ(base->name, "empty base");
  EXPECT_EQ(roleOf(removed, 5), ChildRole::Cut);  // still a cutter
  // A cutter, or a base alone, just goes.
  EXPECT_EQ(childIds(findNode(removeNode(root, 5), 3)), (std::vector<NodeId>{4}));
  EXPECT_TRUE(findNode(removeNode(removeNode(root, 5), 4), 3)->children.empty());
}

TEST(Roles, HidingABaseEmptiesItsDifferenceInsteadOfPromotingACutter) {
  Scene scene;
  // The difference apart from the rest, so that a promoted cutter would show.
  scene.root = editNode(sampleTree(), 3, [](Node& n) { n.transform.translate.x = 4.0; });
  scene.settings.resolution = 32;
  const double whole = test::evaluateCpu(scene).measure.volume;
  Scene withoutDifference = scene;
  withoutDifference.root = removeNode(scene.root, 3);
  withoutDifference.settings.hasBounds = true;
  withoutDifference.settings.bounds = test::evaluateCpu(scene).grid.bounds();
  Scene hiddenBase = withoutDifference;
  hiddenBase.root = editNode(scene.root, 4, [](Node& n) { n.visible = false; });
  // The cylinder that cut the sphere must not appear as a solid of its own.
  EXPECT_NEAR(test::evaluateCpu(hiddenBase).measure.volume,
              test::evaluateCpu(withoutDifference).measure.volume, 1e-9 * whole);
}

TEST(Roles, GhostsAreWhatCutsOrIntersectsTheSelection) {
  // root(1, union) { a(2, box), g(3, difference) { b(4, sphere), c(5, cylinder),
  //   i(7, intersection) { e(8, cone), f(9, torus) } }, d(6, torus) }
  NodePtr root = insertChild(sampleTree(), 3, -1,
                             makeOperationNode(NodeKind::Intersection, 7,
                                               {makePrimitiveNode(NodeKind::Cone, 8),
                                                makePrimitiveNode(NodeKind::Torus, 9)}));
  EXPECT_EQ(ghostCandidates(root), (std::vector<NodeId>{5, 7, 8, 9}));
  EXPECT_TRUE(ghostsOf(root, {}, false).empty());
  EXPECT_EQ(ghostsOf(root, {}, true), (std::vector<NodeId>{5, 7, 8, 9}));
  // The base: the cutters beside it (not what lies inside them).
  EXPECT_EQ(ghostsOf(root, {4}, false), (std::vector<NodeId>{5, 7}));
  // The difference: what it holds. A part that adds elsewhere: none.
  EXPECT_EQ(ghostsOf(root, {3}, false), (std::vector<NodeId>{5, 7, 8, 9}));
  EXPECT_TRUE(ghostsOf(root, {2}, false).empty());
  // A child of an intersection: the other children, and the intersection (it cuts the base).
  EXPECT_EQ(ghostsOf(root, {8}, false), (std::vector<NodeId>{7, 8, 9}));
  // Hidden parts have none.
  NodePtr hidden = editNode(root, 5, [](Node& n) { n.visible = false; });
  EXPECT_EQ(ghostsOf(hidden, {4}, false), (std::vector<NodeId>{7}));
}

TEST(Roles, TheEvaluatorKeepsTheLdisOfGhosts) {
  Scene scene;
  scene.root = sampleTree();
  scene.settings.resolution = 32;
  Scene cutterAlone = scene;
  cutterAlone.root = findNode(scene.root, 5);  // at the origin, like every part of the tree
  cutterAlone.settings.hasBounds = true;
  const EvalResult full = test::evaluateCpu(scene);
  cutterAlone.settings.bounds = full.grid.bounds();
  EvalOptions options;
  options.keep = {5, 99};
  auto backend = std::make_shared<CpuBackend>();
  Evaluator evaluator(backend);
  Progress progress;
  const EvalResult kept = evaluator.evaluate(scene, options, progress);
  ASSERT_EQ(kept.kept.size(), 1u);
  EXPECT_EQ(kept.kept[0].id, 5u);
  EXPECT_NEAR(backend->measure(kept.kept[0].ldi, progress).volume,
              test::evaluateCpu(cutterAlone).measure.volume, 1e-9);
  EXPECT_NEAR(kept.measure.volume, full.measure.volume, 1e-12);
}

TEST(Roles, MovesAreRefusedIntoThemselves) {
  NodePtr root = sampleTree();
  EXPECT_THROW(movePart(root, 3, 4, PlaceMode::Add, 7), Error);
  EXPECT_THROW(movePart(root, 3, 3, PlaceMode::Add, 7), Error);
  EXPECT_THROW(movePart(root, 1, 2, PlaceMode::Add, 7), Error);
  // A cutter dropped onto the base with "add" is united with it: the artist chose it.
  NodePtr moved = movePart(root, 5, 4, PlaceMode::Add, 7);
  EXPECT_EQ(childIds(findNode(moved, 3)), (std::vector<NodeId>{7}));
  EXPECT_EQ(childIds(findNode(moved, 7)), (std::vector<NodeId>{4, 5}));
}

TEST(Roles, APlacementOrMoveIsOneUndoStep) {
  Document doc;
  NodeId box = doc.addNode(NodeKind::Box);
  std::string sentence;
  NodeId hole = doc.place(makePrimitiveNode(NodeKind::Sphere, 1), box, PlaceMode::Cut, &sentence);
  EXPECT_EQ(roleOf(doc.root(), hole), ChildRole::Cut);
  EXPECT_EQ(roleOf(doc.root(), box), ChildRole::Base);
  EXPECT_NE(sentence.find("cuts from"), std::string::npos);
  NodeId other = doc.addNode(NodeKind::Cylinder);
  doc.moveOnto(other, hole, PlaceMode::Cut);
  EXPECT_EQ(roleOf(doc.root(), other), ChildRole::Cut);
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(roleOf(doc.root(), other), ChildRole::Add);
  ASSERT_TRUE(doc.undo());
  ASSERT_TRUE(doc.undo());
  EXPECT_EQ(roleOf(doc.root(), box), ChildRole::Add);
  EXPECT_EQ(findNode(doc.root(), hole), nullptr);
}

// A part dropped onto a sibling of its own group with the role it has lands where it was: no undo
// step, the document not marked changed (an artist's test: an empty "adds to" step and a "*").
TEST(Roles, ADropThatLeavesEveryPartWhereItWasIsNoStep) {
  Document doc;
  const NodeId a = doc.addNode(NodeKind::Box);
  const NodeId b = doc.addNode(NodeKind::Sphere);
  doc.markSaved(doc.path());
  ASSERT_EQ(roleOf(doc.root(), b), ChildRole::Add);
  const NodePtr before = doc.root();
  const std::string lastStep = doc.undoLabel();
  doc.moveOnto(b, a, PlaceMode::Add);
  EXPECT_EQ(doc.root(), before);
  EXPECT_EQ(doc.undoLabel(), lastStep);
  EXPECT_FALSE(doc.dirty());
  // A drop that does change something is still a step.
  doc.moveOnto(b, a, PlaceMode::Cut);
  EXPECT_EQ(roleOf(doc.root(), b), ChildRole::Cut);
  EXPECT_TRUE(doc.dirty());
}

// Every node of `before` outside the subtree of `except` (the moved part) does what it did:
// its role is unchanged, or it is now the first child of a new operation that took its place and
// its role.
void expectRolesKept(const NodePtr& before, const NodePtr& after, NodeId except,
                     const std::string& what) {
  for (NodeId id : treeOrder(before)) {
    if (!findNode(after, id)) continue;
    if (except && findNode(before, except) && isInSubtree(before, except, id)) continue;
    const ChildRole was = roleOf(before, id);
    ChildRole now = roleOf(after, id);
    NodeLocation where;
    locateNode(after, id, &where);
    if (where.parent && !findNode(before, where.parent->id) && where.index == 0)
      now = roleOf(after, where.parent->id);  // wrapped: the new operation plays its role
    if (was == ChildRole::Root) continue;     // a wrapped root: its meaning is the whole scene's
    EXPECT_EQ(now, was) << what << ": node " << id << " changed its role";
    EXPECT_EQ(removesMaterial(after, id), removesMaterial(before, id)) << what << ": node " << id;
  }
}

std::vector<std::string> bundledScenes() {
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(test::assetsDir() + "/scenes"))
    if (entry.path().string().find(".strata.json") != std::string::npos)
      paths.push_back(entry.path().string());
  return paths;
}

// Calls visit(scene file name, root, moved, target, fresh id) for every part of every bundled
// scene and every node it could be dropped onto (not inside itself).
void forEveryMove(
    const std::function<void(const std::string&, const NodePtr&, NodeId, NodeId, NodeId)>& visit) {
  for (const std::string& path : bundledScenes()) {
    const Scene scene = loadScene(path);
    const NodePtr& root = scene.root;
    const NodeId fresh = maxNodeId(root) + 1;
    const std::vector<NodeId> ids = treeOrder(root);
    for (NodeId moved : ids) {
      if (moved == root->id) continue;
      for (NodeId target : ids)
        if (!isInSubtree(root, moved, target))
          visit(std::filesystem::path(path).filename().string(), root, moved, target, fresh);
    }
  }
}

TEST(Roles, EveryMoveInEveryBundledSceneKeepsEveryOtherRole) {
  int moves = 0;
  forEveryMove(
      [&](const std::string& name, const NodePtr& root, NodeId moved, NodeId target, NodeId fresh) {
        for (PlaceMode mode : kModes) {
          const std::string what = name + " move " + std::to_string(moved) + " onto " +
                                   std::to_string(target) + " " + placeModeName(mode);
          NodePtr after;
          try {
            after = movePart(root, moved, target, mode, fresh);
          } catch (const Error&) {
            continue;  // an instance cycle: refused, nothing changed
          }
          expectRolesKept(root, after, moved, what);
          const ChildRole got = roleOf(after, moved);
          if (got != roleFor(mode)) {
            // An operation left empty by the move takes the part as its first child.
            const NodePtr detached = removeKeepingRoles(root, moved, fresh + 1);
            EXPECT_TRUE(findNode(detached, target)->children.empty() &&
                        got == childRole(*findNode(after, target), 0))
                << what << ": the moved part " << roleWord(got);
          }
          ++moves;
        }
      });
  EXPECT_GT(moves, 1000);
}

// The direction a new part placed with `mode` can move the volume: +1 grow, -1 shrink.
int directionOf(const NodePtr& root, NodeId part) {
  const ChildRole role = roleOf(root, part);
  const int own = role == ChildRole::Add || role == ChildRole::Base ? +1 : -1;
  // Every cutter above flips it (the part's own cut is counted in `own`).
  const bool flipped = removesMaterial(root, part) != (role == ChildRole::Cut);
  return flipped ? -own : own;
}

TEST(Roles, PartsPlacedOnEveryNodeOfEveryBundledSceneDoWhatTheModeSays) {
  int checked = 0;
  for (const std::string& path : bundledScenes()) {
    Scene scene = loadScene(path);
    scene.settings.resolution = 32;
    const Bounds grid = test::evaluateCpu(scene).grid.bounds();
    scene.settings.hasBounds = true;  // one grid for every variant: volumes compare exactly
    scene.settings.bounds = grid;
    const double before = test::evaluateCpu(scene).measure.volume;
    const glm::dvec3 centre = grid.center();
    const double size = 0.3 * grid.size().x;
    for (NodeId target : treeOrder(scene.root)) {
      for (PlaceMode mode : kModes) {
        SCOPED_TRACE(std::filesystem::path(path).filename().string() + " onto " +
                     std::to_string(target) + " " + placeModeName(mode));
        auto part = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Sphere, 1));
        part->params.radius = size;
        part->transform.translate = centre;
        NodePtr fresh = withFreshIds(part, maxNodeId(scene.root) + 1);
        Scene placed = scene;
        const PlacePlan plan = planPlacement(scene.root, target, mode);
        placed.root = placePart(scene.root, plan, fresh, fresh->id + 1);
        expectRolesKept(scene.root, placed.root, fresh->id, "place");
        // The plan knows, before the drop, whether the part's material will be taken away, and
        // its sentence says so where that is not what the part's own role says.
        const bool removes = removesMaterial(placed.root, fresh->id);
        EXPECT_EQ(plan.removesMaterial, removes) << plan.sentence;
        const bool ownCut = roleOf(placed.root, fresh->id) == ChildRole::Cut;
        EXPECT_EQ(plan.sentence.find("inside a cutter") != std::string::npos, removes != ownCut)
            << plan.sentence;
        if (!findNode(scene.root, target)->visible) continue;
        // Placed inside a subtree that instances use in another role (or under a shell), the
        // part acts both ways: no direction to check.
        const std::set<int> directions = test::partDirections(placed.root)[fresh->id];
        if (directions.size() != 1) continue;
        EXPECT_EQ(directionOf(placed.root, fresh->id), *directions.begin());
        const double after = test::evaluateCpu(placed).measure.volume;
        if (directionOf(placed.root, fresh->id) > 0)
          EXPECT_GE(after, before * (1 - 1e-9)) << "a part that adds removed material";
        else
          EXPECT_LE(after, before * (1 + 1e-9)) << "a part that removes added material";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100);
}

TEST(Roles, MovingAPartOntoItsOwnPlaceKeepsTheVolume) {
  for (const std::string& path : bundledScenes()) {
    Scene scene = loadScene(path);
    scene.settings.resolution = 32;
    const double before = test::evaluateCpu(scene).measure.volume;
    for (NodeId id : treeOrder(scene.root)) {
      NodeLocation where;
      locateNode(scene.root, id, &where);
      if (!where.parent) continue;
      const ChildRole role = childRole(*where.parent, where.index);
      if (role == ChildRole::Base) continue;  // a base moved away leaves an empty base
      const PlaceMode mode = role == ChildRole::Cut         ? PlaceMode::Cut
                             : role == ChildRole::Intersect ? PlaceMode::Intersect
                                                            : PlaceMode::Add;
      Scene moved = scene;
      moved.root = movePart(scene.root, id, where.parent->id, mode, maxNodeId(scene.root) + 1);
      EXPECT_NEAR(test::evaluateCpu(moved).measure.volume, before, 1e-9 * before)
          << path << " node " << id;
    }
  }
}

// A part moved onto any node with the mode that keeps what it does (modeKeepingEffect: what a
// drag in the outliner does without a key held) has its material taken away from the result
// exactly where it had before. A countersink inside a union of holes dropped onto a part of the
// base took its role's mode (add) and filled its own hole (an artist's test).
TEST(Roles, APartMovedAnywhereWithTheModeKeepingItsEffectStillDoesWhatItDid) {
  int moves = 0, changedMode = 0;
  forEveryMove(
      [&](const std::string& name, const NodePtr& root, NodeId moved, NodeId target, NodeId fresh) {
        const PlaceMode kept = modeKeepingRole(roleOf(root, moved));
        const bool removes = removesMaterial(root, moved);
        const NodePtr without = removeKeepingRoles(root, moved, fresh + 1);
        const PlaceMode mode = modeKeepingEffect(without, target, kept, removes);
        // Onto a cutter's part every placement is cut away (and the reverse): nothing keeps it,
        // and the placement's sentence says so before the drop.
        bool keepable = false;
        for (PlaceMode m : {PlaceMode::Add, PlaceMode::Cut})
          keepable = keepable || planPlacement(without, target, m).removesMaterial == removes;
        if (!keepable) return;
        NodePtr after;
        try {
          after = movePart(root, moved, target, mode, fresh);
        } catch (const Error&) {
          return;  // an instance cycle: refused, nothing changed
        }
        const std::string what =
            name + " move " + std::to_string(moved) + " onto " + std::to_string(target);
        expectRolesKept(root, after, moved, what);
        if (kept != PlaceMode::Intersect) {
          EXPECT_EQ(removesMaterial(after, moved), removes) << what;
        }
        changedMode += mode != kept ? 1 : 0;
        ++moves;
      });
  EXPECT_GT(moves, 300);
  EXPECT_GT(changedMode, 10) << "parts inside cutters moved elsewhere take the other mode";
}

// Grouping (Ctrl+G: a union, an intersection for parts that intersect) any two parts of every
// bundled scene is refused or leaves the result as it was: parts from different places each do
// there what they did (a hole grouped with a part of the base was moved into the base and became
// a peg: an artist's test).
TEST(Roles, EveryGroupOfTwoPartsIsRefusedOrKeepsTheResult) {
  int kept = 0, refused = 0;
  for (const std::string& path : bundledScenes()) {
    Scene scene = loadScene(path);
    scene.settings.resolution = 24;
    const std::vector<NodeId> ids = treeOrder(scene.root);
    if (ids.size() > 40) continue;  // the pairs of the larger scenes add nothing new, only time
    const Bounds grid = test::evaluateCpu(scene).grid.bounds();
    scene.settings.hasBounds = true;  // one grid for every variant: volumes compare exactly
    scene.settings.bounds = grid;
    const double before = test::evaluateCpu(scene).measure.volume;
    const NodeId groupId = maxNodeId(scene.root) + 1;
    for (size_t i = 0; i < ids.size(); ++i)
      for (size_t j = i + 1; j < ids.size(); ++j) {
        const NodeId a = ids[i], b = ids[j];
        if (a == scene.root->id || isInSubtree(scene.root, a, b)) continue;
        const NodeKind kind = roleOf(scene.root, a) == ChildRole::Intersect ? NodeKind::Intersection
                                                                            : NodeKind::Union;
        Scene grouped = scene;
        try {
          grouped.root = groupNodes(scene.root, {a, b}, kind, groupId);
        } catch (const Error&) {
          ++refused;
          continue;
        }
        EXPECT_NEAR(test::evaluateCpu(grouped).measure.volume, before, 1e-9 * before)
            << std::filesystem::path(path).filename().string() << " group " << a << ", " << b;
        ++kept;
      }
  }
  EXPECT_GT(kept, 20);
  EXPECT_GT(refused, 20);
}

// A part grouped with one inside a moved group keeps its place in the world (it went into the
// moved group with its own transform, and jumped by the group's move).
TEST(Roles, AGroupOfPartsFromMovedParentsKeepsEveryPartInPlace) {
  auto inner = makePrimitiveNode(NodeKind::Box, 3);
  auto held = std::make_shared<Node>(*makeOperationNode(NodeKind::Union, 2, {inner}));
  held->transform.translate = glm::dvec3(10.0, 0.0, 0.0);
  held->transform.rotateDegrees = glm::dvec3(0.0, 0.0, 30.0);
  auto outer = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Sphere, 4));
  outer->transform.translate = glm::dvec3(-3.0, 2.0, 1.0);
  outer->transform.scale = glm::dvec3(2.0);
  const NodePtr root = makeOperationNode(NodeKind::Union, 1, {held, outer});
  const glm::dmat4 before = nodeWorldMatrix(root, 4);
  const NodePtr grouped = groupNodes(root, {3, 4}, NodeKind::Union, 5);
  const glm::dmat4 after = nodeWorldMatrix(grouped, 4);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(after[c][r], before[c][r], 1e-9) << c << " " << r;
  EXPECT_EQ(nodeWorldMatrix(grouped, 3), nodeWorldMatrix(root, 3));
  // The same for a part dropped into the moved group, and out of it again.
  const NodePtr movedIn = movePart(root, 4, 3, PlaceMode::Add, 5);
  const NodePtr movedOut = movePart(movedIn, 4, 1, PlaceMode::Add, 7);
  for (const NodePtr& tree : {movedIn, movedOut}) {
    const glm::dmat4 now = nodeWorldMatrix(tree, 4);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(now[c][r], before[c][r], 1e-9) << c << " " << r;
  }
  // A part an instance repeats would carry its copy along: refused.
  auto copy = std::make_shared<Node>();
  copy->kind = NodeKind::Instance;
  copy->id = 6;
  copy->instanceOf = 4;
  const NodePtr repeated = makeOperationNode(NodeKind::Union, 1, {held, outer, copy});
  EXPECT_THROW(groupNodes(repeated, {3, 4}, NodeKind::Union, 7), Error);
  // Turned, into a group stretched along x: no move, turn and scale keeps its shape. Refused.
  auto stretchedGroup = std::make_shared<Node>(*held);
  stretchedGroup->transform.rotateDegrees = glm::dvec3(0.0);
  stretchedGroup->transform.scale = glm::dvec3(2.0, 1.0, 1.0);
  auto turned = std::make_shared<Node>(*outer);
  turned->transform.rotateDegrees = glm::dvec3(0.0, 0.0, 30.0);
  const NodePtr shearing = makeOperationNode(NodeKind::Union, 1, {stretchedGroup, turned});
  EXPECT_THROW(groupNodes(shearing, {3, 4}, NodeKind::Union, 5), Error);
}

// A drop says which instances change with it: those of a group the part leaves or joins (the
// bore dragged out of the cross bore that an instance repeats), not those of groups it only
// moves within.
TEST(Roles, AMoveSaysWhichInstancesChangeWithIt) {
  const Scene scene = loadScene(test::assetsDir() + "/scenes/demo.strata.json");
  const NodePtr& root = scene.root;
  const NodeId fresh = maxNodeId(root) + 1;
  // "bore along x" (18) leaves "cross bore" (17), which "cross bore along y" (19) repeats.
  const NodePtr out = movePart(root, 18, 4, PlaceMode::Cut, fresh);
  const std::string said = instancesChangedNote(root, out, 18);
  EXPECT_NE(said.find("cross bore along y"), std::string::npos) << said;
  EXPECT_NE(said.find("changes with it"), std::string::npos) << said;
  // A bolt hole moved onto another in its own union: no instance of it, none said.
  const NodePtr within = movePart(root, 9, 11, PlaceMode::Add, fresh);
  EXPECT_EQ(instancesChangedNote(root, within, 9), "");
}

// A part made to cut or intersect inside a modifier or a pattern acts on its siblings there (an
// artist's "cuts" on a shell's opening moved it out of the shell, around which a new difference
// cut the finished shell once; in an array it cut one copy, not each).
TEST(Roles, ARoleChangedInsideAModifierOrPatternActsOnItsSiblingsThere) {
  // An array of three boxes, each with a sphere at its centre: made to cut, the sphere cuts
  // every copy.
  NodePtr cube = test::box(glm::dvec3(10.0));
  NodePtr ball = test::sphere(4.0);
  auto array = std::make_shared<Node>(*test::op(NodeKind::Array, {cube, ball}));
  array->pattern.counts = glm::ivec3(3, 1, 1);
  array->pattern.step = glm::dvec3(20.0, 0.0, 0.0);
  NodePtr root = test::op(NodeKind::Union, {array});
  const NodeId fresh = maxNodeId(root) + 1;
  const NodePtr cut = changeRole(root, ball->id, PlaceMode::Cut, fresh);
  const NodePtr arrayAfter = findNode(cut, array->id);
  ASSERT_EQ(arrayAfter->children.size(), 1u);
  EXPECT_EQ(arrayAfter->children[0]->kind, NodeKind::Difference);
  EXPECT_EQ(arrayAfter->children[0]->id, fresh);
  EXPECT_EQ(roleOf(cut, cube->id), ChildRole::Base);
  EXPECT_EQ(roleOf(cut, ball->id), ChildRole::Cut);
  const Scene scene =
      test::makeSceneInBox(cut, 128, glm::dvec3(-6.0, -6.0, -6.0), glm::dvec3(50.0, 6.0, 6.0));
  const double expected = 3.0 * (1000.0 - 4.0 / 3.0 * 3.14159265358979 * 64.0);
  EXPECT_NEAR(test::evaluateCpu(scene).measure.volume, expected, 0.02 * expected);
  // Back to adding: beside the difference, inside the array, the boxes whole again.
  const NodePtr back = changeRole(cut, ball->id, PlaceMode::Add, maxNodeId(cut) + 1);
  EXPECT_EQ(roleOf(back, ball->id), ChildRole::Add);
  EXPECT_TRUE(isInSubtree(back, array->id, ball->id));

  // A shell of a sphere with a cylinder through its top as its opening: made to cut, the
  // cylinder stays inside the shell (still its opening), and two siblings are cut as one union.
  NodePtr body = test::sphere(10.0);
  NodePtr rim = test::torus(8.0, 1.0);
  NodePtr bore = test::cylinder(2.0, 30.0, glm::dvec3(0.0, 0.0, 10.0));
  auto shell = std::make_shared<Node>(*test::modifier(NodeKind::Shell, 1.0, {body, bore, rim}));
  shell->opening = bore->id;
  NodePtr scene2 = test::op(NodeKind::Union, {shell});
  const NodeId fresh2 = maxNodeId(scene2) + 1;
  const NodePtr opened = changeRole(scene2, bore->id, PlaceMode::Cut, fresh2);
  const NodePtr shellAfter = findNode(opened, shell->id);
  ASSERT_EQ(shellAfter->children.size(), 1u);
  const NodePtr inside = shellAfter->children[0];
  EXPECT_EQ(inside->kind, NodeKind::Difference);
  ASSERT_EQ(inside->children.size(), 2u);
  EXPECT_EQ(inside->children[0]->kind, NodeKind::Union);
  EXPECT_EQ(inside->children[0]->id, fresh2 + 1);
  EXPECT_EQ(childIds(inside->children[0]), (std::vector<NodeId>{body->id, rim->id}));
  EXPECT_EQ(inside->children[1]->id, bore->id);
  ASSERT_TRUE(shellOpening(shellAfter));
  EXPECT_EQ(shellOpening(shellAfter)->id, bore->id);
  EXPECT_EQ(roleOf(opened, body->id), ChildRole::Add);
  EXPECT_EQ(roleOf(opened, rim->id), ChildRole::Add);
  // Intersect the same way.
  const NodePtr kept = changeRole(scene2, rim->id, PlaceMode::Intersect, fresh2);
  EXPECT_EQ(findNode(kept, shell->id)->children[0]->kind, NodeKind::Intersection);
  EXPECT_EQ(roleOf(kept, rim->id), ChildRole::Intersect);

  // The only child of a modifier has nothing there to act on: refused, said why.
  NodePtr lone = test::sphere(1.0);
  NodePtr grown = test::modifier(NodeKind::Offset, 0.5, {lone});
  NodePtr scene3 = test::op(NodeKind::Union, {grown, test::box(glm::dvec3(1.0))});
  try {
    changeRole(scene3, lone->id, PlaceMode::Cut, maxNodeId(scene3) + 1);
    ADD_FAILURE() << "the only child of a modifier was made to cut";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing in it to cut"), std::string::npos) << e.what();
  }
  // In a plain union a changed role still wraps the union (movePart): the same as before.
  NodePtr plain = sampleTree();
  EXPECT_EQ(changeRole(plain, 2, PlaceMode::Cut, 7)->kind, NodeKind::Difference);
}

}  // namespace
}  // namespace strata
