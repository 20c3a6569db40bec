// The pure tree edits of engine/document/commands.h: structure, sharing and the rules.
#include <gtest/gtest.h>

#include "engine/document/commands.h"
#include "engine/util/error.h"

namespace strata {
namespace {

// root(1, union) { a(2, box), g(3, difference) { b(4, sphere), c(5, cylinder) }, d(6, torus) }
NodePtr sampleTree() {
  NodePtr b = makePrimitiveNode(NodeKind::Sphere, 4);
  NodePtr c = makePrimitiveNode(NodeKind::Cylinder, 5);
  NodePtr g = makeOperationNode(NodeKind::Difference, 3, {b, c});
  NodePtr a = makePrimitiveNode(NodeKind::Box, 2);
  NodePtr d = makePrimitiveNode(NodeKind::Torus, 6);
  return makeOperationNode(NodeKind::Union, 1, {a, g, d});
}

std::vector<NodeId> childIds(const NodePtr& node) {
  std::vector<NodeId> ids;
  for (const auto& c : node->children) ids.push_back(c->id);
  return ids;
}

TEST(DocumentCommands, EditCopiesOnlyThePathToTheRoot) {
  NodePtr root = sampleTree();
  NodePtr edited = editNode(root, 4, [](Node& n) { n.name = "ball"; });
  EXPECT_NE(edited, root);
  EXPECT_EQ(findNode(edited, 4)->name, "ball");
  EXPECT_EQ(findNode(root, 4)->name, "sphere 4");  // the old snapshot is untouched
  EXPECT_NE(findNode(edited, 3), findNode(root, 3));
  EXPECT_EQ(findNode(edited, 2), findNode(root, 2));  // shared
  EXPECT_EQ(findNode(edited, 5), findNode(root, 5));
  EXPECT_EQ(findNode(edited, 6), findNode(root, 6));
  EXPECT_THROW(editNode(root, 99, [](Node&) {}), Error);
}

TEST(DocumentCommands, InsertAndRemove) {
  NodePtr root = sampleTree();
  NodePtr added = insertChild(root, 3, 1, makePrimitiveNode(NodeKind::Cone, 7));
  EXPECT_EQ(childIds(findNode(added, 3)), (std::vector<NodeId>{4, 7, 5}));
  NodePtr appended = insertChild(root, 1, -1, makePrimitiveNode(NodeKind::Cone, 7));
  EXPECT_EQ(childIds(appended), (std::vector<NodeId>{2, 3, 6, 7}));
  EXPECT_THROW(insertChild(root, 2, 0, makePrimitiveNode(NodeKind::Cone, 7)), Error);  // leaf
  EXPECT_THROW(insertChild(root, 1, 0, makePrimitiveNode(NodeKind::Cone, 4)), Error);  // id used

  NodePtr removed = removeNode(root, 3);
  EXPECT_EQ(childIds(removed), (std::vector<NodeId>{2, 6}));
  EXPECT_EQ(findNode(removed, 4), nullptr);
  EXPECT_THROW(removeNode(root, 1), Error);  // the root
}

TEST(DocumentCommands, RemoveRefusesANodeAnInstanceUses) {
  auto instance = std::make_shared<Node>();
  instance->id = 7;
  instance->kind = NodeKind::Instance;
  instance->instanceOf = 4;
  NodePtr root = insertChild(sampleTree(), 1, -1, instance);
  EXPECT_THROW(removeNode(root, 4), Error);
  EXPECT_THROW(removeNode(root, 3), Error);  // contains the target
  EXPECT_NO_THROW(removeNode(root, 7));      // the instance itself may go
}

TEST(DocumentCommands, DuplicateGivesFreshIdsAndFollowsInnerInstances) {
  auto instance = std::make_shared<Node>();
  instance->id = 7;
  instance->kind = NodeKind::Instance;
  instance->instanceOf = 4;
  NodePtr root = insertChild(sampleTree(), 3, -1, instance);
  NodeId copy = 0;
  NodePtr dup = duplicateNode(root, 3, 8, &copy);
  EXPECT_EQ(copy, 8u);
  EXPECT_EQ(childIds(dup), (std::vector<NodeId>{2, 3, 8, 6}));
  NodePtr group = findNode(dup, 8);
  EXPECT_EQ(group->name, "difference 3 copy");
  EXPECT_EQ(childIds(group), (std::vector<NodeId>{9, 10, 11}));
  EXPECT_EQ(group->children[2]->instanceOf, 9u);  // the copy's instance uses the copied sphere
  EXPECT_EQ(maxNodeId(dup), 11u);
  EXPECT_NO_THROW(checkInstances(dup));
  // Duplicated again: a name of its own (three Ctrl+D made three rows named alike).
  NodeId second = 0, third = 0;
  NodePtr again = duplicateNode(dup, 3, 12, &second);
  again = duplicateNode(again, 3, maxNodeId(again) + 1, &third);
  EXPECT_EQ(findNode(again, second)->name, "difference 3 copy 2");
  EXPECT_EQ(findNode(again, third)->name, "difference 3 copy 3");
  // A copy of a copy (Ctrl+D keeps the copy selected): another copy of the part.
  NodeId fourth = 0;
  again = duplicateNode(again, third, maxNodeId(again) + 1, &fourth);
  EXPECT_EQ(findNode(again, fourth)->name, "difference 3 copy 4");
  EXPECT_EQ(copyName(again, "copy"), "copy");
  EXPECT_EQ(copyName(again, "a copy machine"), "a copy machine copy");
  EXPECT_THROW(duplicateNode(root, 1, 8, &copy), Error);  // root
  EXPECT_THROW(duplicateNode(root, 2, 3, &copy), Error);  // ids in use
}

TEST(DocumentCommands, MoveReordersAndReparents) {
  NodePtr root = sampleTree();
  // Reorder inside the root: d before a.
  NodePtr r1 = moveNode(root, 6, 1, 0);
  EXPECT_EQ(childIds(r1), (std::vector<NodeId>{6, 2, 3}));
  // Move forward within the same parent: a before d (index of d now is 2).
  NodePtr r2 = moveNode(root, 2, 1, 2);
  EXPECT_EQ(childIds(r2), (std::vector<NodeId>{3, 2, 6}));
  // Into another operation, appended.
  NodePtr r3 = moveNode(root, 2, 3, -1);
  EXPECT_EQ(childIds(r3), (std::vector<NodeId>{3, 6}));
  EXPECT_EQ(childIds(findNode(r3, 3)), (std::vector<NodeId>{4, 5, 2}));
  // Out of a group to the root, before d.
  NodePtr r4 = moveNode(root, 5, 1, 2);
  EXPECT_EQ(childIds(r4), (std::vector<NodeId>{2, 3, 5, 6}));
  // In front of itself: nothing changes.
  EXPECT_EQ(moveNode(root, 3, 1, 1), root);
}

TEST(DocumentCommands, NeverDropsANodeIntoItsOwnSubtree) {
  NodePtr root = sampleTree();
  NodePtr nested = moveNode(root, 6, 3, -1);
  nested = groupNodes(nested, {4}, NodeKind::Union, 7);  // 3 { 7 { 4 }, 5, 6 }
  EXPECT_THROW(moveNode(nested, 3, 3, -1), Error);       // itself
  EXPECT_THROW(moveNode(nested, 3, 7, -1), Error);       // its child
  EXPECT_THROW(moveNode(nested, 1, 3, -1), Error);       // the root anywhere
  EXPECT_THROW(moveNode(nested, 2, 4, -1), Error);       // into a leaf
  try {
    moveNode(nested, 3, 7, 0);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("inside it"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(isInSubtree(nested, 3, 4));
  EXPECT_FALSE(isInSubtree(nested, 7, 5));
}

TEST(DocumentCommands, MoveRefusesInstanceCycles) {
  auto instance = std::make_shared<Node>();
  instance->id = 7;
  instance->kind = NodeKind::Instance;
  instance->instanceOf = 3;
  NodePtr root = insertChild(sampleTree(), 1, -1, instance);
  EXPECT_NO_THROW(checkInstances(root));
  EXPECT_THROW(moveNode(root, 7, 3, -1), Error);  // the instance inside what it refers to
}

TEST(DocumentCommands, DropOnEmptySpaceMovesToTheTop) {
  NodePtr root = sampleTree();
  NodePtr top = moveNodeToTop(root, 4, 7);  // union root: appended to it
  EXPECT_EQ(top->id, 1u);
  EXPECT_EQ(childIds(top), (std::vector<NodeId>{2, 3, 6, 4}));

  NodePtr diffRoot = makeOperationNode(
      NodeKind::Difference, 1,
      {makePrimitiveNode(NodeKind::Box, 2),
       makeOperationNode(NodeKind::Union, 3, {makePrimitiveNode(NodeKind::Sphere, 4)})});
  NodePtr wrapped = moveNodeToTop(diffRoot, 4, 5);  // other roots: wrapped in a new union
  EXPECT_EQ(wrapped->id, 5u);
  EXPECT_EQ(wrapped->kind, NodeKind::Union);
  EXPECT_EQ(childIds(wrapped), (std::vector<NodeId>{1, 4}));
  EXPECT_TRUE(findNode(wrapped, 3)->children.empty());
  EXPECT_THROW(moveNodeToTop(root, 1, 7), Error);
}

TEST(DocumentCommands, GroupKeepsTreeOrderAndPlace) {
  NodePtr root = sampleTree();
  NodePtr grouped = groupNodes(root, {6, 2}, NodeKind::Difference, 7);
  EXPECT_EQ(childIds(grouped), (std::vector<NodeId>{7, 3}));
  EXPECT_EQ(childIds(findNode(grouped, 7)), (std::vector<NodeId>{2, 6}));  // tree order
  EXPECT_EQ(findNode(grouped, 7)->kind, NodeKind::Difference);
  // A node inside another selected node goes with its ancestor.
  NodePtr nested = groupNodes(root, {3, 4}, NodeKind::Intersection, 7);
  EXPECT_EQ(childIds(nested), (std::vector<NodeId>{2, 7, 6}));
  EXPECT_EQ(childIds(findNode(nested, 7)), (std::vector<NodeId>{3}));
  // Across parents, doing the same: placed where the first was.
  NodePtr nestedUnion = setOperationKind(root, 3, NodeKind::Union);
  NodePtr across = groupNodes(nestedUnion, {5, 6}, NodeKind::Union, 7);
  EXPECT_EQ(childIds(findNode(across, 3)), (std::vector<NodeId>{4, 7}));
  EXPECT_EQ(childIds(findNode(across, 7)), (std::vector<NodeId>{5, 6}));
  // Parts that do different things are not grouped: one of them would change what it does (a
  // cutter would add, a part beside the base would be cut).
  EXPECT_THROW(groupNodes(root, {5, 6}, NodeKind::Union, 7), Error);
  EXPECT_THROW(groupNodes(root, {4, 2}, NodeKind::Union, 7), Error);
  // The root alone is wrapped.
  NodePtr wrapped = groupNodes(root, {1}, NodeKind::Union, 7);
  EXPECT_EQ(wrapped->id, 7u);
  EXPECT_EQ(wrapped->children[0], root);
  EXPECT_THROW(groupNodes(root, {1, 2}, NodeKind::Union, 7), Error);
  EXPECT_THROW(groupNodes(root, {2}, NodeKind::Box, 7), Error);
}

TEST(DocumentCommands, ChangeOperationKind) {
  NodePtr root = sampleTree();
  NodePtr changed = setOperationKind(root, 3, NodeKind::Intersection);
  EXPECT_EQ(findNode(changed, 3)->kind, NodeKind::Intersection);
  EXPECT_EQ(setOperationKind(root, 3, NodeKind::Difference), root);
  EXPECT_THROW(setOperationKind(root, 2, NodeKind::Union), Error);
  EXPECT_THROW(setOperationKind(root, 3, NodeKind::Sphere), Error);
}

TEST(DocumentCommands, ADefaultNameFollowsTheKindAChosenOneStays) {
  NodePtr fresh = makeOperationNode(NodeKind::Difference, 4, {});
  ASSERT_EQ(fresh->name, "difference 4");
  NodePtr changed = setOperationKind(fresh, 4, NodeKind::Intersection);
  EXPECT_EQ(changed->name, "intersection 4");
  NodePtr named = editNode(fresh, 4, [](Node& n) { n.name = "bracket"; });
  EXPECT_EQ(setOperationKind(named, 4, NodeKind::Union)->name, "bracket");
  // Named for people ("circularArray 23" was the file's word), and the earlier builds' default
  // names still count as Strata's.
  EXPECT_EQ(makeOperationNode(NodeKind::CircularArray, 23, {})->name, "circular array 23");
  NodePtr old = editNode(fresh, 4, [](Node& n) {
    n.kind = NodeKind::CircularArray;
    n.name = "circularArray 4";
  });
  EXPECT_EQ(setOperationKind(old, 4, NodeKind::Array)->name, "array 4");
}

TEST(DocumentCommands, ValidatesParametersAndTransforms) {
  PrimitiveParams p;
  EXPECT_NO_THROW(validateParams(NodeKind::Torus, p));
  p.minorRadius = 2.0;
  EXPECT_THROW(validateParams(NodeKind::Torus, p), Error);
  p = PrimitiveParams();
  p.radius = 0.0;
  EXPECT_THROW(validateParams(NodeKind::Sphere, p), Error);
  p = PrimitiveParams();
  p.segments = 2;
  EXPECT_THROW(validateParams(NodeKind::Cylinder, p), Error);
  Transform t;
  t.scale.y = 0.0;
  EXPECT_THROW(validateTransform(t), Error);
}

TEST(DocumentCommands, MeshPathsBetweenAbsoluteAndRelative) {
  NodePtr mesh = makeMeshNode(2, "m", nullptr, "meshes/../meshes/part.obj", "");
  NodePtr absolute = makeMeshNode(3, "a", nullptr, "/data/x.stl", "");
  NodePtr root = makeOperationNode(NodeKind::Union, 1, {mesh, absolute});
  NodePtr full = absoluteMeshPaths(root, "/w");
  EXPECT_EQ(findNode(full, 2)->meshPath, "/w/meshes/part.obj");
  EXPECT_EQ(findNode(full, 3)->meshPath, "/data/x.stl");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/w/"), 2)->meshPath, "meshes/part.obj");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/w/"), 3)->meshPath, "/data/x.stl");
  // In a folder beside it, under a common one that is not the root: relative (a project's
  // scenes/ and meshes/); farther, or sharing only the root: absolute.
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/w/other"), 2)->meshPath, "../meshes/part.obj");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/w/a/b"), 2)->meshPath, "/w/meshes/part.obj");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/v/other"), 2)->meshPath, "/w/meshes/part.obj");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/v"), 2)->meshPath, "/w/meshes/part.obj");
  EXPECT_EQ(findNode(relativeMeshPaths(full, "/"), 2)->meshPath, "w/meshes/part.obj");
}

}  // namespace
}  // namespace strata
