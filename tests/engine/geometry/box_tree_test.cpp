// BoxTree against a loop over every box: random boxes of mixed sizes, piled-up identical boxes,
// empty boxes, and points on box boundaries.
#include "engine/geometry/box_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace strata {
namespace {

std::vector<uint32_t> bruteForce(const std::vector<Bounds>& boxes, const glm::dvec3& p) {
  std::vector<uint32_t> hits;
  for (uint32_t i = 0; i < boxes.size(); ++i)
    if (!boxes[i].empty() && BoxTree::contains(boxes[i], p)) hits.push_back(i);
  return hits;
}

std::vector<uint32_t> treeHits(const BoxTree& tree, const glm::dvec3& p) {
  std::vector<uint32_t> hits;
  tree.forEachContaining(p, [&](uint32_t i) { hits.push_back(i); });
  std::sort(hits.begin(), hits.end());
  return hits;
}

TEST(BoxTree, MatchesEveryBoxLoop) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-10.0, 10.0), size(0.0, 3.0);
  std::vector<Bounds> boxes;
  for (int i = 0; i < 2000; ++i) {
    Bounds b;
    b.min = glm::dvec3(at(rng), at(rng), at(rng));
    b.max = b.min + glm::dvec3(size(rng), size(rng), size(rng)) * (i % 50 == 0 ? 6.0 : 1.0);
    boxes.push_back(b);
  }
  boxes.push_back(Bounds());                               // empty: never reported
  for (int i = 0; i < 40; ++i) boxes.push_back(boxes[5]);  // a pile of identical boxes
  const BoxTree tree(boxes);
  for (int q = 0; q < 3000; ++q) {
    const glm::dvec3 p = q % 10 == 0 ? boxes[size_t(q) % 2000].max  // on a corner
                                     : glm::dvec3(at(rng), at(rng), at(rng));
    ASSERT_EQ(treeHits(tree, p), bruteForce(boxes, p)) << "query " << q;
  }
  EXPECT_EQ(treeHits(tree, boxes[5].center()).size(), bruteForce(boxes, boxes[5].center()).size());
}

TEST(BoxTree, EmptyAndAllEmpty) {
  const BoxTree none{std::vector<Bounds>{}};
  EXPECT_TRUE(treeHits(none, glm::dvec3(0.0)).empty());
  const BoxTree allEmpty{std::vector<Bounds>(5)};
  EXPECT_TRUE(treeHits(allEmpty, glm::dvec3(0.0)).empty());
}

}  // namespace
}  // namespace strata
