// The per-ray math both backends share: the tie rule, triangle hits, the event gather and the
// sweeps.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "engine/ldi/shared_math.h"

namespace strata {
namespace {

TEST(SharedMath, EdgeSignIsAntisymmetricAndNeverZero) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int64_t> d(-4, 4);
  for (int k = 0; k < 20000; ++k) {
    int64_t au = d(rng) * 128, av = d(rng) * 128, bu = d(rng) * 128, bv = d(rng) * 128;
    int64_t pu = d(rng) * 256, pv = d(rng) * 256;
    int s = edgeSign(au, av, bu, bv, pu, pv);
    if (au == bu && av == bv) {
      EXPECT_EQ(s, 0);
      continue;
    }
    EXPECT_NE(s, 0);
    EXPECT_EQ(s, -edgeSign(bu, bv, au, av, pu, pv));
  }
}

// A fan of triangles around a vertex that sits exactly on a ray: exactly one triangle of the
// fan is hit, whatever the fan's shape.
TEST(SharedMath, RayThroughSharedVertexHitsExactlyOneFanTriangle) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> count(3, 9);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    int n = count(rng);
    std::vector<std::array<double, 3>> ring;
    for (int i = 0; i < n; ++i) {
      double angle = 2 * M_PI * (i + 0.5 + jitter(rng)) / n;
      // Snap ring corners to the lattice too, sometimes exactly onto rays' lines.
      ring.push_back(
          {std::round(std::cos(angle) * 4) / 2, std::round(std::sin(angle) * 4) / 2, jitter(rng)});
    }
    int hits = 0, valid = 0;
    for (int i = 0; i < n; ++i) {
      const auto& a = ring[i];
      const auto& b = ring[(i + 1) % n];
      // Triangle (centre, a, b) in the (u, v) plane of axis z; corners as (x, y, z).
      double p[3][3] = {{0, 0, 0}, {a[0], a[1], a[2]}, {b[0], b[1], b[2]}};
      double normal[3] = {0, 0, 1};
      ProjectedTriangle t = projectTriangle(p, normal, 2, 0, 0, 8, 8);
      if (t.orientation <= 0) continue;  // the fan folds or degenerates here: skip the trial
      ++valid;
      double depth;
      if (hitTriangle(t, 0, 0, &depth)) ++hits;
    }
    if (valid == n) {
      EXPECT_EQ(hits, 1) << "trial " << trial;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000) << "most fans must be valid, or the test checks nothing";
}

// triangleRowSpan gives each row's hits exactly as hitTriangle does ray by ray, on triangles of
// every shape and orientation: corners snapped to the rays' lattice (edges and corners exactly
// on rays, where the perturbation decides), to the sub-cell lattice, and anywhere; slivers,
// triangles wider than the window, windows that start away from the origin. It fails on a run
// that misses an end ray or takes one too many.
TEST(SharedMath, RowSpansAreExactlyTheRaysThatHit) {
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> kind(0, 2), axisPick(0, 2);
  std::uniform_real_distribution<double> anywhere(-3.0, 40.0), depth(-5.0, 5.0);
  std::uniform_int_distribution<int> onRay(-3, 40), sub(-3 * 256, 40 * 256);
  int hits = 0, ends = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int k = kind(rng);
    double p[3][3];
    for (auto& corner : p)
      for (int c = 0; c < 3; ++c)
        corner[c] = k == 0 ? double(onRay(rng)) : k == 1 ? double(sub(rng)) / 256.0 : anywhere(rng);
    if (trial % 7 == 0)  // a sliver: the third corner near the line of the first two
      for (int c = 0; c < 3; ++c) p[2][c] = p[0][c] + (p[1][c] - p[0][c]) * 0.5 + 1e-3 * c;
    const int axis = axisPick(rng);
    for (int c = 0; c < 3; ++c) p[c][axis] = depth(rng);
    const double normal[3] = {0, 0, 1};
    const int firstU = trial % 3 == 0 ? 5 : 0, firstV = trial % 5 == 0 ? -2 : 0;
    const ProjectedTriangle t = projectTriangle(p, normal, axis, firstU, firstV, 32, 30);
    for (int j = t.rayVMin; j <= t.rayVMax; ++j) {
      int first = 0, last = -1;
      triangleRowSpan(t, j, &first, &last);
      for (int i = t.rayUMin; i <= t.rayUMax; ++i) {
        double d = 0.0;
        const bool hit = hitTriangle(t, i, j, &d);
        ASSERT_EQ(hit, i >= first && i <= last) << "trial " << trial << " row " << j << " ray " << i
                                                << ": span [" << first << ", " << last << "]";
        if (hit) {
          ++hits;
          EXPECT_EQ(d, hitDepth(t, i, j));
          if (i == first || i == last) ++ends;
        }
      }
    }
  }
  EXPECT_GT(hits, 100000) << "the triangles must cover rays, or the test checks nothing";
  EXPECT_GT(ends, 10000);
}

// A triangle far outside the window on either side (a tool parked away, up to the 2^51 grid
// units toGridUnits accepts) gives an empty ray range, not one that wrapped around 32 bits.
TEST(SharedMath, FarTrianglesProjectToAnEmptyRange) {
  const double normal[3] = {0, 0, 1};
  for (double offset : {-1e15, -5e9, -3e9, 3e9, 5e9, 1e15}) {
    double p[3][3] = {{offset, 0, 0}, {offset + 2, 0, 0}, {offset, 2, 0}};
    ProjectedTriangle t = projectTriangle(p, normal, 2, 0, 0, 64, 64);
    EXPECT_GT(t.rayUMin, t.rayUMax) << offset;
    double q[3][3] = {{0, offset, 0}, {2, offset, 0}, {0, offset + 2, 0}};
    ProjectedTriangle s = projectTriangle(q, normal, 2, 0, 0, 64, 64);
    EXPECT_GT(s.rayVMin, s.rayVMax) << offset;
  }
  double inside[3][3] = {{1, 1, 0}, {5, 1, 0}, {1, 5, 0}};
  ProjectedTriangle t = projectTriangle(inside, normal, 2, 0, 0, 64, 64);
  EXPECT_EQ(t.rayUMin, 1);
  EXPECT_EQ(t.rayUMax, 5);
}

TEST(SharedMath, NormalEncodingRoundTrips) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  for (int k = 0; k < 10000; ++k) {
    float v[3] = {g(rng), g(rng), g(rng)};
    float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (float& c : v) c /= len;
    float out[3];
    decodeNormal(encodeNormal(v[0], v[1], v[2]), out);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[c], v[c], 1e-4f);
  }
}

TEST(SharedMath, LeafSweepUnitesOverlappingShellsByWinding) {
  // Two overlapping shells on one ray: enter 1, enter 2, exit 3, exit 4 -> one interval [1, 4].
  uint32_t n = encodeNormal(1, 0, 0);
  Surfel in[4] = {{1, n, makeSurfelTag(5, true)},
                  {2, n, makeSurfelTag(5, true)},
                  {3, n, makeSurfelTag(5, false)},
                  {4, n, makeSurfelTag(5, false)}};
  Surfel out[6];
  int k = normalizeLeafRay(in, 4, -1, 100, 5, n, n, out);
  ASSERT_EQ(k, 2);
  EXPECT_EQ(out[0].depth, 1);
  EXPECT_TRUE(surfelEnters(out[0].tag));
  EXPECT_EQ(out[1].depth, 4);
  EXPECT_FALSE(surfelEnters(out[1].tag));
}

TEST(SharedMath, LeafSweepClipsAtTheGridEnds) {
  uint32_t n = encodeNormal(1, 0, 0);
  Surfel in[2] = {{-50, n, makeSurfelTag(1, true)}, {500, n, makeSurfelTag(1, false)}};
  Surfel out[4];
  int k = normalizeLeafRay(in, 2, -1, 10, 1, n, n, out);
  ASSERT_EQ(k, 2);
  EXPECT_EQ(out[0].depth, -1);
  EXPECT_EQ(out[1].depth, 10);
}

TEST(SharedMath, DifferenceFlipsNormalsOfSubtractedSurfels) {
  uint32_t px = encodeNormal(1, 0, 0), nx = encodeNormal(-1, 0, 0);
  // A = [0, 10], B = [4, 6]: A - B = [0, 4] u [6, 10]; the surfel at 4 comes from B's enter.
  RayEvent ev[4] = {{0, nx, makeSurfelTag(1, true), 0},
                    {4, nx, makeSurfelTag(2, true), 1},
                    {6, px, makeSurfelTag(2, false), 1},
                    {10, px, makeSurfelTag(1, false), 0}};
  Surfel out[4];
  int k = combineRayEvents(RayOp::Difference, 2, ev, 4, out);
  ASSERT_EQ(k, 4);
  float n[3];
  decodeNormal(out[1].normal, n);
  EXPECT_NEAR(n[0], 1.0f, 1e-4f);  // leaving A - B at 4 faces +x
  EXPECT_FALSE(surfelEnters(out[1].tag));
  EXPECT_EQ(surfelLeaf(out[1].tag), 2u);
  EXPECT_TRUE(surfelEnters(out[2].tag));
}

// Both backends gather a ray's events with gatherRayEvents: the order must be that of a stable
// sort by depth of the children's lists concatenated (ties in child order, then list order).
TEST(SharedMath, GatherRayEventsOrdersAsAStableSortByDepth) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> children(1, 6), length(0, 5), depth(0, 6);
  for (int trial = 0; trial < 2000; ++trial) {
    const int childCount = children(rng);
    std::vector<std::vector<uint32_t>> offsets(static_cast<size_t>(childCount));
    std::vector<std::vector<Surfel>> surfels(static_cast<size_t>(childCount));
    std::vector<AxisLdiView> views;
    std::vector<RayEvent> expected;
    for (int c = 0; c < childCount; ++c) {
      // Ray 1 of two rays; ray 0 holds one surfel that must not be gathered.
      surfels[size_t(c)].push_back(Surfel{-1.0f, 0u, 0u});
      const int n = length(rng);
      for (int k = 0; k < n; ++k) {
        const Surfel s{float(depth(rng)) * 0.5f, uint32_t(k), uint32_t(trial)};
        surfels[size_t(c)].push_back(s);
        expected.push_back(RayEvent{s.depth, s.normal, s.tag, uint32_t(c)});
      }
      offsets[size_t(c)] = {0u, 1u, uint32_t(1 + n)};
      views.push_back(AxisLdiView{offsets[size_t(c)].data(), surfels[size_t(c)].data()});
    }
    std::stable_sort(expected.begin(), expected.end(),
                     [](const RayEvent& x, const RayEvent& y) { return x.depth < y.depth; });
    ASSERT_EQ(rayEventCount(views.data(), childCount, 1, 1, 0), expected.size());
    std::vector<RayEvent> events(expected.size());
    ASSERT_EQ(gatherRayEvents(views.data(), childCount, 1, 1, 0, events.data()),
              int(expected.size()));
    for (size_t k = 0; k < expected.size(); ++k) {
      EXPECT_EQ(events[k].depth, expected[k].depth);
      EXPECT_EQ(events[k].child, expected[k].child);
      EXPECT_EQ(events[k].normal, expected[k].normal);
    }
  }
}

}  // namespace
}  // namespace strata
