// One part measured alone (engine/jobs/part_measure_job.h): a slab inside a turned, moved group
// has its own volume and thickness, the rest of the scene left out; an instance inside the part
// still finds its target elsewhere in the tree; a missing part is an error; the job finishes on
// its own thread and can be cancelled.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "engine/eval/cpu_backend.h"
#include "engine/jobs/part_measure_job.h"
#include "tests/support/scene_builder.h"

namespace strata::test {
namespace {

PartMeasure measureWhenDone(PartMeasureJob& job) {
  for (int i = 0; i < 6000 && !job.done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(job.done());
  EXPECT_EQ(job.error(), "");
  return job.result();
}

TEST(PartMeasureJob, APartAloneWhereTheSceneHasIt) {
  NodePtr slab = box({4.0, 4.0, 0.5});
  Transform turn;
  turn.translate = glm::dvec3(10.0, 0.0, 3.0);
  turn.rotateDegrees = glm::dvec3(30.0, 0.0, 0.0);
  NodePtr group = withTransform(op(NodeKind::Union, {slab}), turn);
  NodePtr big = sphere(5.0, {-20.0, 0.0, 0.0});
  auto scene = std::make_shared<Scene>(makeScene(op(NodeKind::Union, {group, big}), 64));
  const Scene alone = partScene(*scene, slab->id);
  const Bounds b = nodeBounds(alone.root, alone.root, glm::dmat4(1.0));
  const Bounds expected = nodeBounds(group, group, glm::dmat4(1.0));
  EXPECT_NEAR(glm::length(b.min - expected.min), 0.0, 1e-9);  // placed as in the scene
  EXPECT_NEAR(glm::length(b.max - expected.max), 0.0, 1e-9);

  PartMeasureJob job(scene, slab->id, 96, [] { return std::make_shared<CpuBackend>(); });
  const PartMeasure m = measureWhenDone(job);
  EXPECT_NEAR(m.measure.volume, 8.0, 8.0 * 0.05);  // not the sphere's 524
  EXPECT_NEAR(m.measure.thinnestWall, 0.5, m.h);
  EXPECT_GT(m.measure.thinnestAt.x, 7.0);  // in the slab, not elsewhere
}

TEST(PartMeasureJob, AnInstanceInsideThePartFindsItsTarget) {
  NodePtr target = box(glm::dvec3(2.0), {-30.0, 0.0, 0.0});
  auto instance = std::make_shared<Node>();
  instance->id = 9001;
  instance->name = "copy";
  instance->kind = NodeKind::Instance;
  instance->instanceOf = target->id;
  instance->transform.translate = glm::dvec3(30.0, 0.0, 0.0);
  NodePtr part = op(NodeKind::Union, {instance});
  auto scene = std::make_shared<Scene>(makeScene(op(NodeKind::Union, {target, part}), 64));
  PartMeasureJob job(scene, part->id, 64, [] { return std::make_shared<CpuBackend>(); });
  EXPECT_NEAR(measureWhenDone(job).measure.volume, 8.0, 8.0 * 0.05);  // the box, placed
  EXPECT_THROW(partScene(*scene, 424242), Error);
  PartMeasureJob missing(scene, 424242, 64, [] { return std::make_shared<CpuBackend>(); });
  for (int i = 0; i < 2000 && !missing.done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_NE(missing.error().find("no node with id 424242"), std::string::npos) << missing.error();
  // Cancelled at once: done soon, saying so (or finished first on a fast machine).
  PartMeasureJob cancelled(scene, part->id, 512, [] { return std::make_shared<CpuBackend>(); });
  cancelled.cancel();
  for (int i = 0; i < 2000 && !cancelled.done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(cancelled.done());
}

}  // namespace
}  // namespace strata::test
