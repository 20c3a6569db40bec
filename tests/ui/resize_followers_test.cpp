// What follows a part whose size changes (ui/resize_followers.h): the parts resting on it and
// the cutters through or into it. A base plate made thicker buried the ribs that stood on it and
// left its mounting holes blind (an artist's test).
#include "ui/resize_followers.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "engine/document/commands.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

using test::box;
using test::cylinder;
using test::op;

// `root` with `id` resized by `change`, kept where it rested (keptResting) as the editor does.
NodePtr resized(const NodePtr& root, NodeId id, const std::function<void(Node&)>& change) {
  const NodePtr changed = editNode(root, id, change);
  const Transform t = keptResting(root, changed, id);
  return editNode(changed, id, [&](Node& n) { n.transform = t; });
}

// `after` with the followers' transforms set.
NodePtr followed(const NodePtr& after, const std::vector<ResizeFollower>& followers) {
  NodePtr tree = after;
  for (const ResizeFollower& f : followers)
    tree = editNode(tree, f.id, [&](Node& n) { n.transform = f.transform; });
  return tree;
}

const ResizeFollower* find(const std::vector<ResizeFollower>& followers, NodeId id) {
  const auto it = std::find_if(followers.begin(), followers.end(),
                               [&](const ResizeFollower& f) { return f.id == id; });
  return it == followers.end() ? nullptr : &*it;
}

NodePtr flange() {
  return loadScene(test::assetsDir() + "/scenes/flange_patterns.strata.json").root;
}

// The flange of patterns: the base plate (id 1, 8 mm on the ground) made 20 mm. The ribs (3,
// in a mirror) stood on its top and go up with it; the mounting holes (9) and slots (11), 20 mm
// through it with 6 mm past each face, are lengthened to pass the new top by 6 mm; the bore (6)
// and the bolt holes (7), 40 mm long, still pass and are left, as is the hub (2), which stands on
// the ground beside the plate.
TEST(ResizeFollowers, AThickerPlateKeepsItsRibsOnTopAndItsHolesThrough) {
  const NodePtr root = flange();
  ASSERT_NEAR(selectionBounds(root, {1}).max.z, 8.0, 1e-12);
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 20.0; });
  ASSERT_NEAR(selectionBounds(after, {1}).min.z, 0.0, 1e-9);
  const std::vector<ResizeFollower> followers = resizeFollowers(root, after, 1).followers;
  const NodePtr tree = followed(after, followers);
  ASSERT_TRUE(find(followers, 3));
  EXPECT_EQ(find(followers, 3)->why, ResizeFollower::Why::RestsOn);
  EXPECT_NEAR(selectionBounds(tree, {3}).min.z, 20.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {3}).max.z, 32.0, 1e-9);
  for (NodeId hole : {NodeId(9), NodeId(11)}) {
    SCOPED_TRACE(hole);
    ASSERT_TRUE(find(followers, hole));
    EXPECT_EQ(find(followers, hole)->why, ResizeFollower::Why::CutsThrough);
    const Bounds was = selectionBounds(root, {hole}), now = selectionBounds(tree, {hole});
    EXPECT_NEAR(now.min.z, -6.0, 1e-9);
    EXPECT_NEAR(now.max.z, 26.0, 1e-9);
    EXPECT_NEAR(now.min.x, was.min.x, 1e-9);  // only along z
    EXPECT_NEAR(now.max.y, was.max.y, 1e-9);
  }
  for (NodeId left : {NodeId(2), NodeId(6), NodeId(7)}) EXPECT_FALSE(find(followers, left)) << left;
  EXPECT_EQ(followers.size(), 3u);
  const std::vector<FollowMessage> said =
      resizeFollowingMessages(tree, 1, resizeFollowers(root, after, 1));
  ASSERT_EQ(said.size(), 1u);
  EXPECT_FALSE(said[0].warning);
  EXPECT_EQ(said[0].text,
            "\"base plate\" changed size: \"rib\" moved with it; \"mounting hole\" and \"slot\" "
            "lengthened to stay through it");
  EXPECT_TRUE(resizeFollowers(root, after, 1).buried.empty());
}

// The hub stands on the ground beside the plate, 24 mm tall: a plate made 30 mm covers it. It
// rests on nothing that moved and is left, and said to be buried.
TEST(ResizeFollowers, APartStandingBesideAPlateMadeTallerThanItIsSaidToBeBuried) {
  const NodePtr root = flange();
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 30.0; });
  const ResizeFollowing following = resizeFollowers(root, after, 1);
  EXPECT_EQ(following.buried, std::vector<NodeId>{2});
  EXPECT_FALSE(find(following.followers, 2));
  const std::vector<FollowMessage> said = resizeFollowingMessages(after, 1, following);
  ASSERT_EQ(said.size(), 2u);
  EXPECT_TRUE(said[1].warning);
  EXPECT_EQ(said[1].text.rfind("\"hub\" now lies inside \"base plate\"", 0), 0u);
}

// Made thinner (7.5 mm: its edges' radius of 3.5 needs more than 7), the ribs go down with its
// top; every hole still passes it and is left.
TEST(ResizeFollowers, AThinnerPlateTakesWhatRestsOnItDownAndLeavesHolesThatStillPass) {
  const NodePtr root = flange();
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 7.5; });
  const std::vector<ResizeFollower> followers = resizeFollowers(root, after, 1).followers;
  ASSERT_EQ(followers.size(), 1u);
  EXPECT_EQ(followers[0].id, 3u);
  EXPECT_NEAR(selectionBounds(followed(after, followers), {3}).min.z, 7.5, 1e-9);
}

// A block on the plate and a cap on the block go up together; a hole through the block alone
// is lengthened with it (its bottom still passing the block's), a pocket in the plate's top
// moves with the top, a hole across the plate's middle keeps its fraction of the thickness.
TEST(ResizeFollowers, PartsOnPartsPocketsAndHolesAcrossFollowTheirFaces) {
  const NodePtr plate = box({100.0, 60.0, 8.0}, {0.0, 0.0, 4.0});
  const NodePtr block = box({20.0, 20.0, 20.0}, {10.0, 5.0, 18.0});
  const NodePtr cap = cylinder(4.0, 2.0, {10.0, 5.0, 29.0});
  const NodePtr throughBlock = cylinder(3.0, 24.0, {10.0, 5.0, 18.0});  // 6..30
  const NodePtr pocket = box({10.0, 10.0, 6.0}, {-30.0, 0.0, 8.0});     // 5..11: the top only
  const NodePtr across = cylinder(1.0, 120.0, {0.0, -20.0, 2.0}, {0.0, 90.0, 0.0});  // along x
  const NodePtr root = op(NodeKind::Difference,
                          {op(NodeKind::Union, {plate, block, cap}), throughBlock, pocket, across});
  const NodePtr after = resized(root, plate->id, [](Node& n) { n.params.size.z = 16.0; });
  const std::vector<ResizeFollower> followers = resizeFollowers(root, after, plate->id).followers;
  const NodePtr tree = followed(after, followers);
  EXPECT_NEAR(selectionBounds(tree, {block->id}).min.z, 16.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {cap->id}).min.z, 36.0, 1e-9);
  ASSERT_TRUE(find(followers, throughBlock->id));
  EXPECT_EQ(find(followers, throughBlock->id)->why, ResizeFollower::Why::CutsThrough);
  EXPECT_NEAR(selectionBounds(tree, {throughBlock->id}).min.z, 6.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {throughBlock->id}).max.z, 38.0, 1e-9);
  ASSERT_TRUE(find(followers, pocket->id));
  EXPECT_EQ(find(followers, pocket->id)->why, ResizeFollower::Why::CutsInto);
  EXPECT_NEAR(selectionBounds(tree, {pocket->id}).min.z, 13.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {pocket->id}).max.z, 19.0, 1e-9);
  ASSERT_TRUE(find(followers, across->id));
  EXPECT_NEAR(selectionBounds(tree, {across->id}).center().z, 4.0, 1e-9);  // a quarter up
  EXPECT_NEAR(selectionBounds(tree, {across->id}).size().x, 120.0, 1e-9);
}

// Left as they are: a cutter of another part whose box passes through the plate's, a part on
// the ground beside the plate, and a hole turned 30 degrees about x (a lengthening along z would
// shear it: listed). A cutter resized moves nothing.
TEST(ResizeFollowers, CuttersOfOtherPartsTurnedCuttersAndCuttersResizedAreLeft) {
  const NodePtr plate = box({100.0, 60.0, 8.0}, {0.0, 0.0, 4.0});
  const NodePtr tilted = cylinder(2.0, 20.0, {20.0, 0.0, 4.0}, {30.0, 0.0, 0.0});
  const NodePtr other = box({10.0, 10.0, 10.0}, {0.0, 0.0, 40.0});
  const NodePtr othersHole = cylinder(1.0, 60.0, {0.0, 0.0, 20.0});  // passes the plate's box too
  const NodePtr beside = box({10.0, 10.0, 30.0}, {0.0, 0.0, 15.0});  // on the ground, in the plate
  const NodePtr root = op(NodeKind::Union, {op(NodeKind::Difference, {plate, tilted}),
                                            op(NodeKind::Difference, {other, othersHole}), beside});
  const NodePtr after = resized(root, plate->id, [](Node& n) { n.params.size.z = 20.0; });
  const ResizeFollowing following = resizeFollowers(root, after, plate->id);
  EXPECT_TRUE(following.followers.empty());
  EXPECT_EQ(following.leftTurned, std::vector<NodeId>{tilted->id});
  EXPECT_TRUE(following.buried.empty());
  const NodePtr longer = editNode(root, othersHole->id, [](Node& n) { n.params.height = 80.0; });
  EXPECT_TRUE(resizeFollowers(root, longer, othersHole->id).followers.empty());
}

// A gizmo drag asks from the tree where it began, every frame: the same followers, not counted
// twice, whatever the tree the last frame left.
TEST(ResizeFollowers, AskedFromTheStartOfADragTheyAreWhereOneStepPutsThem) {
  const NodePtr root = flange();
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 20.0; });
  const std::vector<ResizeFollower> once = resizeFollowers(root, after, 1).followers;
  const std::vector<ResizeFollower> again =
      resizeFollowers(root, followed(after, once), 1).followers;
  ASSERT_EQ(once.size(), again.size());
  for (size_t i = 0; i < once.size(); ++i) {
    EXPECT_EQ(once[i].id, again[i].id);
    EXPECT_EQ(once[i].transform, again[i].transform);
  }
}

}  // namespace
}  // namespace strata::ui
