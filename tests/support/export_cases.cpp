#include "tests/support/export_cases.h"

#include <cmath>

#include "engine/eval/cpu_backend.h"
#include "engine/eval/evaluator.h"
#include "engine/export/export_scene.h"
#include "engine/export/job_estimate.h"
#include "engine/geometry/mesh_check.h"
#include "engine/util/error.h"
#include "tests/support/scene_builder.h"

namespace strata::test {

std::shared_ptr<const TriangleMesh> facetedTorus(double major, double minor, int around,
                                                 int across) {
  auto m = std::make_shared<TriangleMesh>();
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const double u = 2 * M_PI * i / around, v = 2 * M_PI * j / across;
      const double r = major + minor * std::cos(v);
      m->positions.push_back({r * std::cos(u), r * std::sin(u), minor * std::sin(v)});
    }
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < across; ++j) {
      const uint32_t a = uint32_t(i * across + j), b = uint32_t(((i + 1) % around) * across + j),
                     c = uint32_t(((i + 1) % around) * across + (j + 1) % across),
                     d = uint32_t(i * across + (j + 1) % across);
      m->triangles.push_back({a, b, c});
      m->triangles.push_back({a, c, d});
    }
  return m;
}

NodePtr foldedSliver() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {{0.961176, 0.501176, 0.501176},
                     {-1.72941, -0.6, -0.581176},
                     {-0.6, -0.236863, -0.6},
                     {-0.6, -0.8, -0.6},
                     {-0.6, -0.6, -0.4},
                     {-0.6, -0.6, -0.8}};
  mesh->triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                     {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  prepareMesh(*mesh);
  Transform t;
  t.translate = glm::dvec3(-1.0);
  t.scale = glm::dvec3(-0.3, 0.3, 0.3);
  return withTransform(meshLeaf(mesh), t);
}

Scene barsWithAGap(double gapFrom, double gapTo, int resolution) {
  return makeScene(
      op(NodeKind::Union, {box({gapFrom + 50.0, 5.0, 5.0}, {(gapFrom - 50.0) / 2.0, 0.0, 0.0}),
                           box({50.0 - gapTo, 5.0, 5.0}, {(gapTo + 50.0) / 2.0, 0.0, 0.0})}),
      resolution);
}

Scene barsCloserThanTheProbesCell(int resolution, int* probeCells) {
  const Scene any = barsWithAGap(-1.0, 1.0, resolution);
  Progress quiet;
  const JobEstimate estimate =
      estimateExport(any, ExportOptions{}, "bars.stl", std::make_shared<CpuBackend>(), quiet);
  if (!estimate.probed) throw Error("barsCloserThanTheProbesCell: the export is not probed");
  const Grid probe = Evaluator::gridFor(any, estimate.probeCells);
  const Grid job = Evaluator::gridFor(any, resolution);
  // The probe's nodes either side of x = 0, and the gap half-way between them.
  const double below = probe.origin.x + std::floor(-probe.origin.x / probe.h) * probe.h;
  const double middle = below + 0.5 * probe.h, half = 0.15 * probe.h;
  if (2.0 * half < 2.0 * job.h)
    throw Error("barsCloserThanTheProbesCell: the export's cells would not see the gap");
  if (probeCells) *probeCells = estimate.probeCells;
  return barsWithAGap(middle - half, middle + half, resolution);
}

}  // namespace strata::test
