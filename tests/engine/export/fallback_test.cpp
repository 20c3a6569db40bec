// Out-of-memory fallbacks: smaller tiles first, then the CPU, with a notice each time.
#include <gtest/gtest.h>

#include <algorithm>

#include "engine/document/commands.h"
#include "engine/export/fallback.h"
#include "engine/jobs/preview_worker.h"
#include "tests/support/mesh_invariants.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

// A CPU backend with a pretend memory limit: grids (windows) with more than `maxCells` cells
// along any axis "do not fit".
class SmallMemoryBackend : public CpuBackend {
 public:
  explicit SmallMemoryBackend(int maxCells) : maxCells_(maxCells) {}
  std::string description() const override { return "small-memory test backend"; }
  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override {
    if (std::max({grid.cells.x, grid.cells.y, grid.cells.z}) > maxCells_)
      throw BackendOutOfMemory("pretend: out of device memory");
    return CpuBackend::sampleMesh(mesh, objectToWorld, grid, leafId, progress);
  }

 private:
  int maxCells_;
};

TEST(Fallback, ExportRetriesWithSmallerTilesAndGetsTheSameMesh) {
  Scene s = makeScene(op(NodeKind::Difference, {box({2, 2, 2}), sphere(1.2)}), 160);
  std::vector<std::string> notices;
  Progress progress;
  Evaluator small(std::make_shared<SmallMemoryBackend>(100));
  ExportMesh a = contourWithFallback(s, small, ContourOptions{0, 256}, progress, nullptr,
                                     [&](const std::string& n) { notices.push_back(n); });
  ASSERT_EQ(notices.size(), 2u);  // 256 -> 128 (still too big) -> 64 fits
  EXPECT_NE(notices[0].find("tiles of 128"), std::string::npos) << notices[0];
  EXPECT_NE(notices[1].find("tiles of 64"), std::string::npos) << notices[1];
  Evaluator cpu(std::make_shared<CpuBackend>());
  ExportMesh b = contourScene(s, cpu, ContourOptions{0, 256}, progress);
  EXPECT_TRUE(a.mesh.positions == b.mesh.positions);
  EXPECT_TRUE(a.mesh.triangles == b.mesh.triangles);
}

TEST(Fallback, ExportAndEvaluationFallBackToTheCpu) {
  Scene s = makeScene(sphere(1.0), 96);
  std::vector<std::string> notices;
  Progress progress;
  Evaluator tiny(std::make_shared<SmallMemoryBackend>(10));
  ExportMesh mesh = contourWithFallback(s, tiny, ContourOptions{0, 256}, progress, nullptr,
                                        [&](const std::string& n) { notices.push_back(n); });
  EXPECT_TRUE(isWatertight(mesh.mesh));
  ASSERT_FALSE(notices.empty());
  EXPECT_NE(notices.back().find("on the CPU"), std::string::npos) << notices.back();

  notices.clear();
  std::shared_ptr<Backend> used;
  EvalResult r = evaluateWithFallback(
      tiny, s, {}, progress, [&](const std::string& n) { notices.push_back(n); }, &used);
  ASSERT_EQ(notices.size(), 1u);
  ASSERT_TRUE(used);
  EXPECT_NE(used->description().find("cpu"), std::string::npos);
  EXPECT_GT(r.measure.volume, 4.0);
}

// A backend that cannot evaluate modifiers.
class NoModifierBackend : public CpuBackend {
 public:
  std::string description() const override { return "no-modifier test backend"; }
  LdiHandle offset(const LdiHandle& l, double d, Progress& p) override {
    return Backend::offset(l, d, p);  // throws, saying what to do
  }
  bool evaluatesModifiers() const override { return false; }
};

TEST(Fallback, ModifiersAreEvaluatedOnTheCpuWhereTheBackendCannot) {
  auto round = std::make_shared<Node>(*makeOperationNode(NodeKind::Round, 50, {box({2, 2, 2})}));
  round->amount = 0.25;
  Scene s = makeScene(round, 64);
  Progress progress;
  Evaluator plain(std::make_shared<NoModifierBackend>());
  try {
    plain.evaluate(s, EvalOptions{}, progress);
    ADD_FAILURE() << "the backend evaluated a modifier";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--backend cpu"), std::string::npos) << e.what();
  }
  std::vector<std::string> notices;
  ExportMesh mesh = contourWithFallback(s, plain, ContourOptions{0, 256}, progress, nullptr,
                                        [&](const std::string& n) { notices.push_back(n); });
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_NE(notices[0].find("on the CPU"), std::string::npos) << notices[0];
  EXPECT_TRUE(isWatertight(mesh.mesh));

  PreviewWorker worker(std::make_shared<NoModifierBackend>(), 32);
  worker.request(std::make_shared<Scene>(s), 64, false, 1);
  ASSERT_TRUE(worker.waitUntilIdle(std::chrono::seconds(60)));
  std::shared_ptr<const PreviewResult> result = worker.takeResult();
  ASSERT_TRUE(result);
  EXPECT_TRUE(result->error.empty()) << result->error;
  EXPECT_GT(result->splats->count(), 0u);
  bool said = false;
  for (const auto& w : result->stats.warnings) said |= w.find("on the CPU") != std::string::npos;
  EXPECT_TRUE(said);
}

}  // namespace
}  // namespace strata::test
