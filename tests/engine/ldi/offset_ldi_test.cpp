// Offsets of LDIs (engine/ldi/offset_ldi.h): grown and shrunk analytic solids, shells and
// roundings built from offsets, at two resolutions with tolerances that shrink with h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "engine/eval/cpu_backend.h"
#include "engine/ldi/combine_ldi.h"
#include "engine/ldi/offset_ldi.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The root LDI of `root` evaluated on the box [-1.6, 1.6]^3 at `resolution` cells.
std::shared_ptr<const Ldi> sampled(const NodePtr& root, int resolution) {
  Scene scene = makeSceneInBox(root, resolution, glm::dvec3(-1.6), glm::dvec3(1.6));
  EvalResult result = evaluateCpu(scene);
  return CpuBackend().download(result.root);
}

double volume(const Ldi& ldi) {
  return measureLdi(ldi).volume;
}

// Signed distances to the exact solids (negative inside).
double sphereDistance(const glm::dvec3& p, double r) {
  return glm::length(p) - r;
}
double boxDistance(const glm::dvec3& p, double half) {
  const glm::dvec3 q = glm::abs(p) - glm::dvec3(half);
  return glm::length(glm::max(q, glm::dvec3(0.0))) +
         std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

// The largest |exact(p)| over the world positions p of every surfel of `ldi`, in cells.
template <typename Exact>
double worstSurfelDistance(const Ldi& ldi, Exact exact) {
  const Grid& g = ldi.grid;
  double worst = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const AxisLdi& a = ldi.axes[size_t(axis)];
    const int64_t raysU = g.cells[u] + 1;
    for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray)
      for (uint32_t k = a.offsets[size_t(ray)]; k < a.offsets[size_t(ray) + 1]; ++k) {
        glm::dvec3 p;
        p[axis] = g.origin[axis] + g.h * double(a.surfels[k].depth);
        p[u] = g.origin[u] + g.h * double(g.first[u] + ray % raysU);
        p[v] = g.origin[v] + g.h * double(g.first[v] + ray / raysU);
        worst = std::max(worst, std::abs(exact(p)) / g.h);
      }
  }
  return worst;
}

struct OffsetCase {
  const char* name;
  NodePtr solid;
  double distance;
  double volume;                                   // exact
  double area;                                     // of the offset surface
  std::function<double(const glm::dvec3&)> exact;  // signed distance to the exact offset
  // How far (cells) a surfel may lie from it: a small fraction on smooth surfaces; about a cell
  // where the solid has sharp edges and corners, which lie between the rays that sample it
  // (the nearest samples of a cube's edge are up to h / sqrt 2 from it).
  double tolerance;
};

class OffsetAnalytic : public ::testing::TestWithParam<int> {};

// Every surfel of the offset lies on the exact offset surface within a fraction of a cell; the
// volume (measured ray by ray, so within half a cell times the area for any solid) agrees.
TEST_P(OffsetAnalytic, GrownAndShrunkSolidsLieOnTheExactOffset) {
  const std::vector<OffsetCase> cases = {
      {"sphere grown by 0.25", sphere(1.0), 0.25, 4.0 / 3.0 * kPi * std::pow(1.25, 3),
       4 * kPi * 1.25 * 1.25, [](const glm::dvec3& p) { return sphereDistance(p, 1.25); }, 0.2},
      {"sphere shrunk by 0.25", sphere(1.0), -0.25, 4.0 / 3.0 * kPi * std::pow(0.75, 3),
       4 * kPi * 0.75 * 0.75, [](const glm::dvec3& p) { return sphereDistance(p, 0.75); }, 0.2},
      {"cube grown by 0.25", box(glm::dvec3(2.0)), 0.25,
       8 + 6 + 3 * kPi * 0.125 + 4.0 / 3.0 * kPi * 0.015625, 24 + 12 * kPi * 0.25 + kPi,
       [](const glm::dvec3& p) { return boxDistance(p, 1.0) - 0.25; }, 1.25},
      {"cube shrunk by 0.25", box(glm::dvec3(2.0)), -0.25, 3.375, 6 * 1.5 * 1.5,
       [](const glm::dvec3& p) { return boxDistance(p, 0.75); }, 0.2},
  };
  EXPECT_NEAR(cases[0].volume, 8.18123, 1e-5);
  EXPECT_NEAR(cases[1].volume, 1.76715, 1e-5);
  EXPECT_NEAR(cases[2].volume, 15.2435, 1e-4);
  for (const OffsetCase& c : cases) {
    auto in = sampled(c.solid, GetParam());
    const double h = in->grid.h;
    auto out = offsetLdi(*in, c.distance);
    const double v = volume(*out), worst = worstSurfelDistance(*out, c.exact);
    std::printf("%-22s h %.4f: volume %.5f (exact %.5f), farthest surfel %.3f h\n", c.name, h, v,
                c.volume, worst);
    EXPECT_NEAR(v, c.volume, 0.5 * h * c.area) << c.name << " at h " << h;
    EXPECT_LT(worst, c.tolerance) << c.name << " at h " << h;
  }
}

TEST_P(OffsetAnalytic, ShellAndRoundingFromOffsets) {
  // A shell of thickness 0.1 of the unit sphere: S minus its inward offset (1.13516).
  auto ball = sampled(sphere(1.0), GetParam());
  const double h = ball->grid.h;
  auto shell = combineLdis(RayOp::Difference, {ball, offsetLdi(*ball, -0.1)}, ball->grid);
  const double shellVolume = 4.0 / 3.0 * kPi * (1.0 - std::pow(0.9, 3));
  EXPECT_NEAR(shellVolume, 1.13516, 1e-5);
  const double shellWorst = worstSurfelDistance(*shell, [](const glm::dvec3& p) {
    return std::min(std::abs(sphereDistance(p, 1.0)), std::abs(sphereDistance(p, 0.9)));
  });
  // The cube [-1, 1]^3 rounded with r = 0.25 (an opening): the cube [-0.75, 0.75]^3 grown by
  // 0.25 (7.69902).
  auto cube = sampled(box(glm::dvec3(2.0)), GetParam());
  auto rounded = offsetLdi(*offsetLdi(*cube, -0.25), 0.25);
  const double roundedVolume =
      1.5 * 1.5 * 1.5 + 6 * 1.5 * 1.5 * 0.25 + 3 * kPi * 0.0625 * 1.5 + 4.0 / 3.0 * kPi * 0.015625;
  EXPECT_NEAR(roundedVolume, 7.69902, 1e-5);
  const double roundedWorst = worstSurfelDistance(
      *rounded, [](const glm::dvec3& p) { return boxDistance(p, 0.75) - 0.25; });
  std::printf(
      "h %.4f: shell %.5f (exact %.5f), farthest surfel %.3f h; rounded cube %.5f (exact "
      "%.5f), farthest surfel %.3f h\n",
      h, volume(*shell), shellVolume, shellWorst, volume(*rounded), roundedVolume, roundedWorst);
  EXPECT_NEAR(volume(*shell), shellVolume, 0.5 * h * 4 * kPi * (1.0 + 0.81));
  EXPECT_LT(shellWorst, 0.2);
  EXPECT_NEAR(volume(*rounded), roundedVolume, 0.5 * h * 24);
  EXPECT_LT(roundedWorst, 1.25);  // the inner cube's edges, between rays
}

INSTANTIATE_TEST_SUITE_P(Resolutions, OffsetAnalytic, ::testing::Values(48, 96));

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Offsets of real meshes from ../shared/data, grown and shrunk by 3% of their size at 96 cells:
// a sample of the result's surfels lies at the offset distance from the mesh (brute force over
// every triangle), within about a cell (sharp edges lie between rays).
TEST(OffsetRealMeshes, SurfelsLieAtTheDistanceFromTheMesh) {
  for (const char* file : {"fandisk.obj", "bunny.obj"}) {
    auto mesh = dataMesh(file);
    Bounds bounds;
    for (const auto& p : mesh->positions) bounds.include(p);
    const double size = glm::length(bounds.max - bounds.min);
    const double d = 0.03 * size;
    Scene scene = makeSceneInBox(meshLeaf(mesh), 96, bounds.min - glm::dvec3(2 * d),
                                 bounds.max + glm::dvec3(2 * d));
    auto in = CpuBackend().download(evaluateCpu(scene).root);
    const Grid& g = in->grid;
    for (double distance : {d, -d}) {
      auto out = offsetLdi(*in, distance);
      double worst = 0.0, sum = 0.0;
      int samples = 0;
      const AxisLdi& a = out->axes[0];
      const int64_t raysU = g.cells[1] + 1;
      const size_t step = std::max<size_t>(1, a.surfels.size() / 300);
      for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray)
        for (uint32_t k = a.offsets[size_t(ray)]; k < a.offsets[size_t(ray) + 1]; ++k) {
          if (k % step != 0) continue;
          const glm::dvec3 p(g.origin.x + g.h * double(a.surfels[k].depth),
                             g.origin.y + g.h * double(g.first[1] + ray % raysU),
                             g.origin.z + g.h * double(g.first[2] + ray / raysU));
          double nearest = std::numeric_limits<double>::infinity();
          for (const auto& t : mesh->triangles)
            nearest = std::min(nearest, glm::length(p - closestOnTriangle(p, mesh->positions[t[0]],
                                                                          mesh->positions[t[1]],
                                                                          mesh->positions[t[2]])));
          const double error = std::abs(nearest - std::abs(distance)) / g.h;
          worst = std::max(worst, error);
          sum += error;
          ++samples;
        }
      std::printf("%s offset %+.4f (%.1f cells): %d surfels, mean error %.3f h, worst %.3f h\n",
                  file, distance, distance / g.h, samples, sum / samples, worst);
      ASSERT_GT(samples, 100);
      EXPECT_LT(sum / samples, 0.25) << file << " " << distance;
      EXPECT_LT(worst, 1.25) << file << " " << distance;
    }
  }
}

}  // namespace
}  // namespace strata::test
