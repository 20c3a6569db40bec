// What follows a part whose size changes (ui/resize_followers.h): the parts resting on it, the
// parts built into it and the cutters through or into it. A base plate made thicker buried the
// ribs that stood on it and the hub that stood through it and left its mounting holes blind; the
// first answer moved holes in proportion to the plate's length, off the plate and into the bore,
// and stacked parts followed one level only (artists' tests).
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
using Why = ResizeFollower::Why;

// `root` with `id` resized by `change`, kept where it rested (keptResting) as the editor does.
NodePtr resized(const NodePtr& root, NodeId id, const std::function<void(Node&)>& change) {
  const NodePtr changed = editNode(root, id, change);
  const Transform t = keptResting(root, changed, id);
  return editNode(changed, id, [&](Node& n) { n.transform = t; });
}

// `after` with the followers' transforms and parameters set.
NodePtr followed(const NodePtr& after, const std::vector<ResizeFollower>& followers) {
  NodePtr tree = after;
  for (const ResizeFollower& f : followers)
    tree = editNode(tree, f.id, [&](Node& n) {
      n.transform = f.transform;
      if (f.params) n.params = *f.params;
    });
  return tree;
}

const ResizeFollower* find(const std::vector<ResizeFollower>& followers, NodeId id) {
  const auto it = std::find_if(followers.begin(), followers.end(),
                               [&](const ResizeFollower& f) { return f.id == id; });
  return it == followers.end() ? nullptr : &*it;
}

NodePtr scene(const std::string& name) {
  return loadScene(test::assetsDir() + "/scenes/" + name + ".strata.json").root;
}

// The flange of patterns: the base plate (id 1, 8 mm on the ground) made 20 mm. The ribs (3, in
// a mirror) stood on its top and go up with it. The hub (2) stands on the ground through the
// plate and 16 mm out of it: 16 mm out of it still, its height now 36 mm (in its parameters).
// The bore (6), bolt holes (7, a circular array), mounting holes (9, an array) and slots (11)
// pass both faces: each passes them by as much as before.
TEST(ResizeFollowers, AThickerPlateKeepsItsRibsOnTopItsHubOutAndItsHolesThrough) {
  const NodePtr root = scene("flange_patterns");
  ASSERT_NEAR(selectionBounds(root, {1}).max.z, 8.0, 1e-12);
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 20.0; });
  ASSERT_NEAR(selectionBounds(after, {1}).min.z, 0.0, 1e-9);
  const ResizeFollowing following = resizeFollowers(root, after, 1);
  const std::vector<ResizeFollower>& followers = following.followers;
  const NodePtr tree = followed(after, followers);
  ASSERT_TRUE(find(followers, 3));
  EXPECT_EQ(find(followers, 3)->why, Why::Moved);
  EXPECT_NEAR(selectionBounds(tree, {3}).min.z, 20.0, 1e-9);
  ASSERT_TRUE(find(followers, 2));
  EXPECT_EQ(find(followers, 2)->why, Why::Stretched);
  EXPECT_NEAR(selectionBounds(tree, {2}).min.z, 0.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {2}).max.z, 36.0, 1e-9);
  EXPECT_NEAR(findNode(tree, 2)->params.height, 36.0, 1e-9);
  EXPECT_EQ(findNode(tree, 2)->transform.scale, glm::dvec3(1.0));
  struct Hole {
    NodeId id;
    double low, high;
  } holes[] = {{6, -8.0, 44.0}, {7, -8.0, 44.0}, {9, -6.0, 26.0}, {11, -6.0, 26.0}};
  for (const Hole& hole : holes) {
    SCOPED_TRACE(hole.id);
    ASSERT_TRUE(find(followers, hole.id));
    EXPECT_EQ(find(followers, hole.id)->why, Why::Stretched);
    EXPECT_TRUE(find(followers, hole.id)->cuts);
    const Bounds was = selectionBounds(root, {hole.id}), now = selectionBounds(tree, {hole.id});
    EXPECT_NEAR(now.min.z, hole.low, 1e-9);
    EXPECT_NEAR(now.max.z, hole.high, 1e-9);
    EXPECT_NEAR(now.min.x, was.min.x, 1e-9);  // only along z
    EXPECT_NEAR(now.max.y, was.max.y, 1e-9);
    EXPECT_EQ(findNode(tree, hole.id)->transform.scale, glm::dvec3(1.0));  // in its size
  }
  EXPECT_EQ(followers.size(), 6u);
  EXPECT_TRUE(following.leftAlone.empty());
  EXPECT_TRUE(following.buried.empty());
  const std::vector<FollowMessage> said = resizeFollowingMessages(tree, 1, following);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_FALSE(said[0].warning);
  EXPECT_EQ(said[0].text,
            "\"base plate\" changed size: \"rib\" moved with it; \"hub\" resized with it; "
            "\"bore\", \"bolt hole\" and 2 more kept through it");
}

// Made thinner (7.5 mm: its edges' radius of 3.5 needs more than 7) the ribs go down with its
// top and the hub stands as far out of it; made shorter or narrower about its middle, nothing
// follows: the holes of the bolt circle, the arrays and the slots stay where they were (the first
// answer moved them in proportion, two mounting holes off the plate and the bolt holes into the
// bore), the ribs stay on the top, which did not move.
TEST(ResizeFollowers, AThinnerPlateTakesItsTopsPartsDownAndAShorterOneMovesNothing) {
  const NodePtr root = scene("flange_patterns");
  const NodePtr thinner = resized(root, 1, [](Node& n) { n.params.size.z = 7.5; });
  const std::vector<ResizeFollower> followers = resizeFollowers(root, thinner, 1).followers;
  const NodePtr tree = followed(thinner, followers);
  EXPECT_NEAR(selectionBounds(tree, {3}).min.z, 7.5, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {2}).max.z, 23.5, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {9}).max.z, 13.5, 1e-9);
  for (const glm::dvec3 size : {glm::dvec3(100.0, 80.0, 8.0), glm::dvec3(140.0, 60.0, 8.0)}) {
    const NodePtr smaller = resized(root, 1, [&](Node& n) { n.params.size = size; });
    const ResizeFollowing none = resizeFollowers(root, smaller, 1);
    EXPECT_TRUE(none.followers.empty()) << none.followers.front().id;
    EXPECT_TRUE(none.leftAlone.empty());
  }
}

// The demo's plate core made 16 mm thick: the pedestal on it goes up, and with it the o-ring
// around the pedestal and the bunny on it (stacked parts followed one level only: an artist's
// test); the capsules along its edges keep their ends on its faces; the bolt holes stay through
// and the countersinks in its top go up with it.
TEST(ResizeFollowers, StackedAndBuiltInPartsFollowTheDemosPlate) {
  const NodePtr root = scene("demo");
  const NodePtr after = resized(root, 4, [](Node& n) { n.params.size.z = 16.0; });
  const ResizeFollowing following = resizeFollowers(root, after, 4);
  const NodePtr tree = followed(after, following.followers);
  for (NodeId id : {NodeId(7), NodeId(20), NodeId(21)}) {
    SCOPED_TRACE(id);
    ASSERT_TRUE(find(following.followers, id));
    EXPECT_EQ(find(following.followers, id)->why, Why::Moved);
    EXPECT_NEAR(selectionBounds(tree, {id}).min.z - selectionBounds(root, {id}).min.z, 6.0, 1e-6);
  }
  for (NodeId edge : {NodeId(5), NodeId(6)}) {
    EXPECT_NEAR(selectionBounds(tree, {edge}).max.z, 16.0, 1e-9);
    EXPECT_NEAR(selectionBounds(tree, {edge}).min.z, 0.0, 1e-9);
  }
  for (NodeId hole : {NodeId(9), NodeId(11), NodeId(13), NodeId(15)})
    EXPECT_GT(selectionBounds(tree, {hole}).max.z, 16.0);
  for (NodeId sink : {NodeId(10), NodeId(12), NodeId(14), NodeId(16)})
    EXPECT_NEAR(selectionBounds(tree, {sink}).max.z, 16.5, 1e-9);
  EXPECT_TRUE(following.leftAlone.empty());
  EXPECT_TRUE(following.buried.empty());
}

// A block on a plate and a cap on the block go up together; a hole through the block that also
// reaches into the plate moves up with the plate's top (through the block still); a pocket in
// the plate's top moves with the top; a hole across the plate's middle stays where it was.
TEST(ResizeFollowers, PartsOnPartsAndPocketsFollowTheirFaces) {
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
  EXPECT_NEAR(selectionBounds(tree, {throughBlock->id}).min.z, 14.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {throughBlock->id}).max.z, 38.0, 1e-9);
  ASSERT_TRUE(find(followers, pocket->id));
  EXPECT_EQ(find(followers, pocket->id)->why, Why::Moved);
  EXPECT_NEAR(selectionBounds(tree, {pocket->id}).min.z, 13.0, 1e-9);
  EXPECT_NEAR(selectionBounds(tree, {pocket->id}).max.z, 19.0, 1e-9);
  EXPECT_FALSE(find(followers, across->id));
}

// Left as they are: a cutter of another part whose box passes through the plate's, a part on
// the ground beside the plate, a plate a boss is sunk into when the boss is resized. Left alone
// and said: a hole turned 30 degrees about x (a lengthening along z would shear it), copies of a
// hole arrayed round the x axis (a lengthening along z would not move them alike). A cutter
// resized moves nothing.
TEST(ResizeFollowers, WhatDoesNotBelongIsLeftAndWhatCannotFollowIsSaid) {
  const NodePtr plate = box({100.0, 60.0, 8.0}, {0.0, 0.0, 4.0});
  const NodePtr tilted = cylinder(2.0, 20.0, {20.0, 0.0, 4.0}, {30.0, 0.0, 0.0});
  const NodePtr ringed = cylinder(1.0, 20.0, {-20.0, 0.0, 4.0});
  auto ring = std::make_shared<Node>(*op(NodeKind::CircularArray, {ringed}));
  ring->pattern.axis = 0;
  ring->pattern.count = 4;
  ring->pattern.angle = 360.0;
  const NodePtr other = box({10.0, 10.0, 10.0}, {0.0, 0.0, 40.0});
  const NodePtr othersHole = cylinder(1.0, 60.0, {0.0, 0.0, 20.0});  // passes the plate's box too
  const NodePtr beside = box({10.0, 10.0, 30.0}, {70.0, 0.0, 15.0});
  const NodePtr root =
      op(NodeKind::Union, {op(NodeKind::Difference, {plate, tilted, NodePtr(ring)}),
                           op(NodeKind::Difference, {other, othersHole}), beside});
  const NodePtr after = resized(root, plate->id, [](Node& n) { n.params.size.z = 20.0; });
  const ResizeFollowing following = resizeFollowers(root, after, plate->id);
  EXPECT_TRUE(following.followers.empty());
  EXPECT_EQ(following.leftAlone, (std::vector<NodeId>{tilted->id, ringed->id}));
  EXPECT_TRUE(following.buried.empty());
  EXPECT_TRUE(
      resizeFollowers(root, editNode(root, othersHole->id, [](Node& n) { n.params.height = 80.0; }),
                      othersHole->id)
          .followers.empty());
  // A boss sunk 1 mm into the plate, made taller about its middle: the plate stays.
  const NodePtr boss = cylinder(5.0, 6.0, {0.0, 0.0, 10.0});  // 7..13
  const NodePtr sunk = op(NodeKind::Union, {box({100.0, 60.0, 8.0}, {0.0, 0.0, 4.0}), boss});
  const NodePtr taller = editNode(sunk, boss->id, [](Node& n) { n.params.height = 12.0; });
  EXPECT_TRUE(resizeFollowers(sunk, taller, boss->id).followers.empty());
  // The flange's hub made wider (radius 28 to 32): the plate it stands through reaches past it
  // along x and y and stays as it is (it grew with the hub's radius: a review).
  const NodePtr flangeRoot = scene("flange_patterns");
  const NodePtr wider = editNode(flangeRoot, 2, [](Node& n) { n.params.radius = 32.0; });
  const ResizeFollowing hub = resizeFollowers(flangeRoot, wider, 2);
  EXPECT_FALSE(find(hub.followers, 1));
  EXPECT_TRUE(hub.leftAlone.empty());
  // The ribs, which reach into the hub's wall, move out with it, the mirrored one the other way
  // (each copy as its own box says: the leaf's change gives the image its mirror image).
  ASSERT_TRUE(find(hub.followers, 3));
  EXPECT_NEAR(selectionBounds(followed(wider, hub.followers), {3}).min.x, 30.0, 1e-9);
}

// A part that follows nothing and that the plate made thicker now covers is said to be buried.
TEST(ResizeFollowers, APartThePlateNowCoversIsSaidToBeBuried) {
  const NodePtr plate = box({100.0, 60.0, 8.0}, {0.0, 0.0, 4.0});
  const NodePtr floating = box({4.0, 4.0, 2.0}, {0.0, 0.0, 21.0});  // 20..22, above the top
  const NodePtr root = op(NodeKind::Union, {plate, floating});
  const NodePtr after = resized(root, plate->id, [](Node& n) { n.params.size.z = 30.0; });
  const ResizeFollowing following = resizeFollowers(root, after, plate->id);
  EXPECT_TRUE(following.followers.empty());
  EXPECT_EQ(following.buried, std::vector<NodeId>{floating->id});
  const std::vector<FollowMessage> said = resizeFollowingMessages(after, plate->id, following);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_TRUE(said[0].warning);
  EXPECT_NE(said[0].text.find("now lies inside"), std::string::npos) << said[0].text;
}

// The gizmo's scale of one primitive goes into its size where its parameters hold it: a rounded
// box keeps round corners (they turned oval: an artist's test), a cylinder its circle; a scale
// that would make an ellipse or mirror the part stays a scale; one that squeezes a rounded box
// under its corners' radius makes the radius fit.
TEST(ScaleIntoSize, APrimitiveScaledByTheGizmoChangesItsSize) {
  const NodePtr plate = scene("flange_patterns");
  const NodePtr start = findNode(plate, 1);  // rounded box 140 x 80 x 8, radius 3.5
  Transform now = start->transform;
  now.scale = glm::dvec3(1.0, 1.0, 2.5);
  PrimitiveParams sized;
  ASSERT_TRUE(scaleIntoSize(*start, &now, &sized));
  EXPECT_EQ(now.scale, glm::dvec3(1.0));
  EXPECT_EQ(sized.size, glm::dvec3(140.0, 80.0, 20.0));
  EXPECT_EQ(sized.radius, 3.5);
  // 4 mm: under twice the corners' radius, which is made to fit (as the inspector does).
  now.scale = glm::dvec3(1.0, 1.0, 0.5);
  std::vector<FittedParam> fitted;
  ASSERT_TRUE(scaleIntoSize(*start, &now, &sized, &fitted));
  EXPECT_EQ(now.scale.z, 1.0);
  EXPECT_EQ(sized.size.z, 4.0);
  EXPECT_EQ(sized.radius, 1.999);
  ASSERT_EQ(fitted.size(), 1u);
  EXPECT_STREQ(fitted[0].label, "corner radius");
  now.scale = glm::dvec3(1.0, 1.0, 2.0);  // nothing to fit
  ASSERT_TRUE(scaleIntoSize(*start, &now, &sized, &fitted));
  EXPECT_EQ(sized.radius, 3.5);
  EXPECT_TRUE(fitted.empty());
  now.scale = glm::dvec3(1.0, 1.0, -1.0);  // a mirroring
  EXPECT_FALSE(scaleIntoSize(*start, &now, &sized));
  const NodePtr hub = findNode(plate, 2);  // cylinder r 28, h 24
  now = hub->transform;
  now.scale = glm::dvec3(1.5, 1.5, 0.5);
  ASSERT_TRUE(scaleIntoSize(*hub, &now, &sized));
  EXPECT_EQ(sized.radius, 42.0);
  EXPECT_EQ(sized.height, 12.0);
  now.scale = glm::dvec3(1.5, 1.0, 1.0);  // an ellipse
  EXPECT_FALSE(scaleIntoSize(*hub, &now, &sized));
  // A capsule: its radius across, its whole length (height + 2 radius) along z.
  auto capsule = std::make_shared<Node>(*makePrimitiveNode(NodeKind::Capsule, 50));
  capsule->params.radius = 5.0;
  capsule->params.height = 50.0;
  now = capsule->transform;
  now.scale = glm::dvec3(2.0, 2.0, 1.5);
  ASSERT_TRUE(scaleIntoSize(*capsule, &now, &sized));
  EXPECT_EQ(sized.radius, 10.0);
  EXPECT_EQ(sized.height, 90.0 - 20.0);
}

// A gizmo drag asks from the tree where it began, every frame: the same followers, not counted
// twice, whatever the tree the last frame left.
TEST(ResizeFollowers, AskedFromTheStartOfADragTheyAreWhereOneStepPutsThem) {
  const NodePtr root = scene("flange_patterns");
  const NodePtr after = resized(root, 1, [](Node& n) { n.params.size.z = 20.0; });
  const std::vector<ResizeFollower> once = resizeFollowers(root, after, 1).followers;
  const std::vector<ResizeFollower> again =
      resizeFollowers(root, followed(after, once), 1).followers;
  ASSERT_EQ(once.size(), again.size());
  for (size_t i = 0; i < once.size(); ++i) {
    EXPECT_EQ(once[i].id, again[i].id);
    EXPECT_EQ(once[i].transform, again[i].transform);
    EXPECT_EQ(once[i].params, again[i].params);
  }
}

}  // namespace
}  // namespace strata::ui
