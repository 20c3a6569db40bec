// `strata render`'s path without a window (ui/headless_gl.h, ui/scene_render.h): an EGL context
// with no display, the scene evaluated and drawn as the viewport draws it, the section plane
// applied. Skips, saying why, where EGL offers no OpenGL (libEGL missing).
#include <gtest/gtest.h>

#include <memory>

#include "engine/eval/cpu_backend.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"
#include "ui/headless_gl.h"
#include "ui/scene_render.h"

namespace strata::ui {
namespace {

std::unique_ptr<HeadlessGl> headlessOrSkipReason(std::string* why) {
  try {
    return std::make_unique<HeadlessGl>();
  } catch (const Error& e) {
    *why = e.what();
    return nullptr;
  }
}

struct Rgb {
  int r, g, b;
};
Rgb pixel(const SceneRender& render, int width, int x, int y) {
  const uint8_t* p = &render.pixels[(size_t(y) * size_t(width) + size_t(x)) * 4];
  return {p[0], p[1], p[2]};
}

TEST(HeadlessRender, RendersASceneWithoutAWindow) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  EXPECT_NE(gl->description().find("EGL"), std::string::npos) << gl->description();
  Scene scene = test::makeScene(test::sphere(1.0), 64);
  auto red = std::make_shared<Node>(*scene.root);
  red->color = glm::vec3(0.9f, 0.1f, 0.1f);
  scene.root = red;
  auto backend = std::make_shared<CpuBackend>();
  SceneRenderOptions options;
  options.width = 200;
  options.height = 160;
  options.view = AxisView::Back;
  options.grid = false;
  Progress progress;
  SceneRender whole = renderScene(scene, "", backend, options, progress);
  ASSERT_EQ(whole.pixels.size(), size_t(200) * 160 * 4);
  EXPECT_GT(whole.splats, 1000u);
  auto reddish = [](Rgb p) { return p.r > p.g + 60 && p.r > p.b + 60; };
  EXPECT_TRUE(reddish(pixel(whole, 200, 100, 80)));
  EXPECT_FALSE(reddish(pixel(whole, 200, 2, 2)));

  // Cut at y = 0 and seen from +y: the cap, flat (no highlight), fills the disc.
  options.section.on = true;
  options.section.axis = 1;
  options.section.at = 0.5;
  SceneRender cut = renderScene(scene, "", backend, options, progress);
  EXPECT_TRUE(reddish(pixel(cut, 200, 100, 80)));
  int differing = 0;
  for (int y = 0; y < 160; ++y)
    for (int x = 0; x < 200; ++x) {
      Rgb a = pixel(whole, 200, x, y), b = pixel(cut, 200, x, y);
      differing += (a.r != b.r || a.g != b.g || a.b != b.b) ? 1 : 0;
    }
  EXPECT_GT(differing, 1000) << "the cap looks different from the sphere's back";
}

}  // namespace
}  // namespace strata::ui
