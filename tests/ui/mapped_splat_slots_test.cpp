// The host path's mapped splat buffers (ui/mapped_splat_slots.h) in a headless GL context: what
// is lent when, that a region comes back only once given back and copied from, and that the
// drawn buffer receives exactly the splats written into the region. Skips where EGL offers no
// OpenGL 4.4 (persistent mapping).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "engine/util/error.h"
#include "ui/headless_gl.h"
#include "ui/mapped_splat_slots.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {
namespace {

std::unique_ptr<HeadlessGl> glOrSkip(std::string* why) {
  try {
    auto gl = std::make_unique<HeadlessGl>();
    if (!MappedSplatSlots::supported()) {
      *why = "no persistent mapping on " + gl->description();
      return nullptr;
    }
    return gl;
  } catch (const Error& e) {
    *why = e.what();
    return nullptr;
  }
}

Splat splatNumber(uint32_t k) {
  Splat s{};
  s.position[0] = float(k);
  s.position[1] = float(k) * 0.5f;
  s.position[2] = -float(k);
  s.normal = k * 2654435761u;
  s.leafAxis = (k << 2) | (k % 3);
  return s;
}

TEST(MappedSplatSlots, LendsRegionsAgainOnlyOnceGivenBackAndCopiedFrom) {
  std::string why;
  auto gl = glOrSkip(&why);
  if (!gl) GTEST_SKIP() << why;
  MappedSplatSlots slots;
  std::shared_ptr<HostSplatLender> lender = slots.lender();
  const SplatLevels levels = SplatLevels::flat(1000);
  // Nothing is mapped before a result asks: the first goes elsewhere, and sizes the buffers.
  EXPECT_EQ(lender->lend(1000, levels), nullptr);
  for (int frame = 0; frame < MappedSplatSlots::kSlots; ++frame) slots.maintain();  // one a frame
  EXPECT_TRUE(slots.made());
  EXPECT_FALSE(slots.pinned()) << "nothing pins them here";
  EXPECT_GE(slots.bytes(), MappedSplatSlots::kSlots * 1000 * sizeof(Splat));

  std::vector<std::shared_ptr<LentHostSplats>> held;
  for (int i = 0; i < MappedSplatSlots::kSlots; ++i) {
    held.push_back(lender->lend(1000, levels));
    ASSERT_NE(held.back(), nullptr) << "slot " << i;
  }
  EXPECT_EQ(lender->lend(10, SplatLevels::flat(10)), nullptr) << "every region is held";
  EXPECT_EQ(slots.lentCount(), size_t(MappedSplatSlots::kSlots));

  // The first region filled and copied into the drawn buffer on the GPU.
  ViewportRenderer renderer;
  for (uint32_t k = 0; k < 1000; ++k) held[0]->writableData()[k] = splatNumber(k);
  SplatShape shape;
  shape.cellSize = 1.0;
  ASSERT_TRUE(slots.holds(*held[0]));
  ASSERT_TRUE(slots.copyInto(renderer, *held[0], shape));
  EXPECT_EQ(slots.copiedCount(), 1u);
  std::vector<Splat> drawn(1000);
  glBindBuffer(GL_ARRAY_BUFFER, renderer.splatBuffer());
  glGetBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(drawn.size() * sizeof(Splat)), drawn.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  for (uint32_t k = 0; k < 1000; ++k) {
    const Splat want = splatNumber(k);
    ASSERT_EQ(std::memcmp(&drawn[k], &want, sizeof(Splat)), 0) << "splat " << k;
  }

  // Given back: lendable again only after a maintain() saw its copy done.
  const Splat* first = held[0]->hostData();
  held[0].reset();
  EXPECT_EQ(lender->lend(1000, levels), nullptr) << "not before maintain()";
  glFinish();
  slots.maintain();
  std::shared_ptr<LentHostSplats> again = lender->lend(1000, levels);
  ASSERT_NE(again, nullptr);
  EXPECT_EQ(again->hostData(), first) << "the region given back";

  // Not splats of these buffers: nothing copied.
  HostSplats elsewhere(std::vector<Splat>(10));
  EXPECT_FALSE(slots.holds(elsewhere));
  EXPECT_FALSE(slots.copyInto(renderer, elsewhere, shape));

  // A larger result grows a free slot (one a frame) while the others stay as they are.
  held.clear();
  again.reset();
  EXPECT_EQ(lender->lend(5000, SplatLevels::flat(5000)), nullptr);
  slots.maintain();
  EXPECT_NE(lender->lend(5000, SplatLevels::flat(5000)), nullptr);

  // After stopLending nothing is lent, and the buffers go as they come back.
  slots.stopLending();
  EXPECT_EQ(lender->lend(10, SplatLevels::flat(10)), nullptr);
  slots.maintain();
  EXPECT_EQ(slots.bytes(), 0u);
}

}  // namespace
}  // namespace strata::ui
