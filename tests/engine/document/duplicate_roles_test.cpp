// Duplicate never changes what an existing part does, and the copy plays the original's role.
// For every node of every bundled scene: duplicating leaves the result's volume as it was (the
// copy coincides with the original), and moving the copy away changes the volume in the
// direction of the original's role: a part that adds material (a union's child, a difference's
// base) can only grow the result, one that removes material (a cutter, an intersection's child)
// can only shrink it, with the direction flipped under every cutter above it. Parts that act in
// both directions (inside a subtree that instances use in another role, or under a shell) have no
// direction to check and are skipped (tests/support/part_directions.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "engine/document/commands.h"
#include "engine/io/scene_file.h"
#include "tests/support/part_directions.h"
#include "tests/support/scene_builder.h"

namespace strata {
namespace {

double volumeOf(const Scene& scene) {
  return test::evaluateCpu(scene).measure.volume;
}

TEST(DuplicateRoles, EveryNodeOfEveryBundledSceneKeepsEveryRole) {
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::assetsDir() + "/scenes")) {
    if (entry.path().string().find(".strata.json") == std::string::npos) continue;
    Scene scene = loadScene(entry.path().string());
    scene.settings.resolution = 32;
    // One grid for every variant (a moved copy would grow an automatic one): volumes compare
    // exactly.
    const Bounds grid = test::evaluateCpu(scene).grid.bounds();
    scene.settings.hasBounds = true;
    scene.settings.bounds = grid;
    const double before = volumeOf(scene);
    const double size = scene.settings.bounds.size().x;
    for (const auto& [id, directions] : test::partDirections(scene.root)) {
      if (directions.size() != 1) continue;
      const int direction = *directions.begin();
      SCOPED_TRACE(entry.path().filename().string() + " node " + std::to_string(id));
      NodeId copyId = 0;
      Scene duplicated = scene;
      duplicated.root = duplicateNode(scene.root, id, maxNodeId(scene.root) + 1, &copyId);
      EXPECT_NEAR(volumeOf(duplicated), before, 1e-9 * before) << "the duplicate changed the part";
      Scene moved = duplicated;
      moved.root = editNode(duplicated.root, copyId, [&](Node& n) {
        n.transform.translate.x += 0.13 * size;
        n.transform.translate.y += 0.07 * size;
      });
      const double after = volumeOf(moved);
      if (direction > 0)
        EXPECT_GE(after, before * (1 - 1e-9)) << "a copy of a part that adds material removed some";
      else
        EXPECT_LE(after, before * (1 + 1e-9))
            << "a copy of a part that removes material added some";
      ++checked;
    }
  }
  EXPECT_GT(checked, 40);
}

TEST(DuplicateRoles, TheBaseOfADifferenceIsUnitedWithItsCopy) {
  // The trap that was seen: Ctrl+D on a difference's first child made the copy a cutter and
  // the part vanished.
  auto base = test::box(glm::dvec3(2.0));
  auto cutter = test::sphere(0.7);
  auto root = test::op(NodeKind::Difference, {base, cutter});
  NodeId copy = 0;
  NodePtr after = duplicateNode(root, base->id, maxNodeId(root) + 1, &copy);
  ASSERT_EQ(after->children.size(), 2u);
  const NodePtr& group = after->children[0];
  EXPECT_EQ(group->kind, NodeKind::Union);
  ASSERT_EQ(group->children.size(), 2u);
  EXPECT_EQ(group->children[0]->id, base->id);  // the original keeps its id: instances hold
  EXPECT_EQ(group->children[1]->id, copy);
  EXPECT_EQ(after->children[1]->id, cutter->id);
  // A cutter's copy is a cutter right after it.
  NodePtr twice = duplicateNode(root, cutter->id, maxNodeId(root) + 1, &copy);
  ASSERT_EQ(twice->children.size(), 3u);
  EXPECT_EQ(twice->children[2]->id, copy);
}

}  // namespace
}  // namespace strata
