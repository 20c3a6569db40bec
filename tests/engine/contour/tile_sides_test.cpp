// The node sides and boundary cells of a tile as bit planes (tile_sides.h) against the per-node
// definition they implement: each ray's vote counted surfel by surfel (rayVote's rule: a node
// counts the surfels at or before its depth), the majority, the outer faces.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/contour/contour_cells.h"
#include "engine/contour/contour_tile.h"
#include "engine/contour/tile_sides.h"

namespace strata {
namespace {

// Random sorted surfel lists for every ray of a window, as a TileView reads them. Depths are
// global grid units, many exactly on nodes (the tie rule), some before or after the window.
struct RandomWindow {
  std::vector<uint32_t> offsets[3];
  std::vector<Surfel> surfels[3];

  RandomWindow(const TileView& t, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> count(0, 5), kind(0, 3);
    std::uniform_real_distribution<float> frac(0.0f, 1.0f);
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const int64_t rays = int64_t(t.cells[u] + 1) * (t.cells[v] + 1);
      offsets[a].push_back(0);
      for (int64_t r = 0; r < rays; ++r) {
        std::vector<float> depths;
        const int n = count(rng);
        for (int s = 0; s < n; ++s) {
          const float lo = float(t.first[a]) - 2.0f, span = float(t.cells[a]) + 4.0f;
          float d = lo + span * frac(rng);
          if (kind(rng) == 0) d = std::floor(d);  // exactly on a node
          depths.push_back(d);
        }
        std::sort(depths.begin(), depths.end());
        for (size_t s = 0; s < depths.size(); ++s)
          surfels[a].push_back(Surfel{depths[s], 0u, makeSurfelTag(1, s % 2 == 0)});
        offsets[a].push_back(uint32_t(surfels[a].size()));
      }
    }
  }
};

int referenceVotes(const TileView& t, const int n[3]) {
  int votes = 0;
  for (int a = 0; a < 3; ++a) {
    const int64_t ray = tileRay(t, a, n);
    int passed = 0;
    for (uint32_t s = t.offsets[a][ray]; s < t.offsets[a][ray + 1]; ++s)
      passed += t.surfels[a][s].depth <= float(t.first[a] + n[a]) ? 1 : 0;
    votes += passed % 2;
  }
  return votes;
}

void expectSidesMatchTheDefinition(const glm::ivec3& first, const glm::ivec3& cells,
                                   const glm::ivec3& globalCells, uint32_t seed) {
  TileView t = makeTileView(first, cells, globalCells, first, first + cells);
  RandomWindow window(t, seed);
  for (int a = 0; a < 3; ++a) {
    t.offsets[a] = window.offsets[a].data();
    t.surfels[a] = window.surfels[a].data();
  }
  TileSides sides;
  decideTileSides(&t, &sides, nullptr);

  const int nx = cells.x + 1, ny = cells.y + 1, nz = cells.z + 1;
  std::vector<uint8_t> inside(size_t(nx) * ny * nz);
  uint64_t disagreements = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int n[3] = {i, j, k};
        const int votes = referenceVotes(t, n);
        bool face = false;
        for (int a = 0; a < 3; ++a) {
          const int g = t.first[a] + n[a];
          face = face || g == 0 || g == t.globalCells[a];
        }
        const uint8_t side = decideNodeSide(uint8_t(votes), face);
        inside[size_t(tileNode(t, i, j, k))] = side;
        disagreements += (votes == 1 || votes == 2) ? 1 : 0;
        ASSERT_EQ(nodeInside(t, i, j, k), side) << "node " << i << " " << j << " " << k;
        ASSERT_EQ(nodeUnanimous(t, i, j, k), votes == 0 || votes == 3 ? 1u : 0u)
            << "node " << i << " " << j << " " << k;
      }
  EXPECT_EQ(sides.disagreements, disagreements);

  std::vector<uint32_t> boundary;
  std::vector<uint8_t> masks;
  for (int k = 0; k < cells.z; ++k)
    for (int j = 0; j < cells.y; ++j)
      for (int i = 0; i < cells.x; ++i) {
        uint8_t mask = 0;
        for (int c = 0; c < 8; ++c)
          mask = uint8_t(
              mask |
              inside[size_t(tileNode(t, i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)))]
                  << c);
        if (mask != 0 && mask != 255) {
          boundary.push_back(uint32_t(tileCell(t, i, j, k)));
          masks.push_back(mask);
        }
      }
  ASSERT_FALSE(boundary.empty());
  EXPECT_EQ(sides.boundary, boundary);
  EXPECT_EQ(sides.boundaryMasks, masks);
  EXPECT_EQ(t.boundaryCount, int64_t(boundary.size()));
  EXPECT_EQ(t.boundary, sides.boundary.data());
}

TEST(TileSides, BitPlanesMatchTheVotesOfEveryNode) {
  // Rows of more than one word, windows at the grid's lower and upper faces and inside it.
  expectSidesMatchTheDefinition({0, 0, 0}, {130, 7, 9}, {130, 7, 9}, 1);
  expectSidesMatchTheDefinition({5, 3, 2}, {63, 11, 17}, {100, 100, 100}, 2);
  expectSidesMatchTheDefinition({37, 0, 60}, {64, 5, 40}, {101, 50, 100}, 3);
  expectSidesMatchTheDefinition({1, 1, 1}, {3, 3, 3}, {4, 4, 4}, 4);
  expectSidesMatchTheDefinition({0, 10, 0}, {200, 3, 2}, {200, 13, 2}, 5);
}

}  // namespace
}  // namespace strata
