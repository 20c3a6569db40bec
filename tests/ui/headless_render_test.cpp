// `strata render`'s path without a window (ui/headless_gl.h, ui/scene_render.h): an EGL context
// with no display, the scene evaluated and drawn as the viewport draws it, the section plane
// applied. Skips, saying why, where EGL offers no OpenGL (libEGL missing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
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

// Levels of detail (engine/ldi/splats.h, ViewportRenderer::detailLevel): a sphere of 256 cells in
// a small image, where a cell is a fraction of a pixel, is drawn from a quarter or a sixteenth of
// its splats and looks as it does with every splat; filling the image, it is drawn whole.
TEST(HeadlessRender, LevelsOfDetailLookLikeEverySplat) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  Scene scene = test::makeScene(test::sphere(1.0), 256);
  auto backend = std::make_shared<CpuBackend>();
  SceneRenderOptions options;
  options.width = 160;
  options.height = 120;
  options.grid = false;
  Progress progress;
  SceneRender lod = renderScene(scene, "", backend, options, progress);
  options.everySplat = true;
  SceneRender every = renderScene(scene, "", backend, options, progress);
  EXPECT_EQ(every.detailLevel, 0);
  EXPECT_EQ(every.splatsDrawn, every.splats);
  EXPECT_GE(lod.detailLevel, 1);
  EXPECT_LT(double(lod.splatsDrawn), 0.3 * double(lod.splats));
  // Pixel by pixel: no holes, no grown silhouette, shading within a few levels.
  int far = 0, covered = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      Rgb a = pixel(lod, 160, x, y), b = pixel(every, 160, x, y);
      const int d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
      far += d > 24 ? 1 : 0;
      Rgb corner = pixel(every, 160, 0, 0);
      covered += (b.r != corner.r || b.g != corner.g || b.b != corner.b) ? 1 : 0;
    }
  EXPECT_GT(covered, 3000) << "the sphere fills part of the image";
  EXPECT_LT(far, covered / 100) << "pixels that differ visibly between the levels";

  // Close up (a large image: cells of several pixels): every splat.
  options.everySplat = false;
  options.width = 1600;
  options.height = 1200;
  SceneRender near = renderScene(scene, "", backend, options, progress);
  EXPECT_EQ(near.detailLevel, 0);
  EXPECT_EQ(near.splatsDrawn, near.splats);
}

}  // namespace
}  // namespace strata::ui
