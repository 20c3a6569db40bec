// `strata render`'s path without a window (ui/headless_gl.h, ui/scene_render.h): an EGL context
// with no display, the scene evaluated and drawn as the viewport draws it, the section plane
// applied. Skips, saying why, where EGL offers no OpenGL (libEGL missing).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include "engine/eval/cpu_backend.h"
#include "engine/io/scene_file.h"
#include "tests/support/scene_builder.h"
#include "ui/headless_gl.h"
#include "ui/scene_render.h"
#include "ui/viewport_renderer.h"

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

// A unit sphere of `resolution` cells evaluated on the CPU, its splats uploaded to `renderer`;
// returns how many.
size_t uploadSphere(ViewportRenderer& renderer, int resolution = 128) {
  Scene scene = test::makeScene(test::sphere(1.0), resolution);
  EvalResult result = test::evaluateCpu(scene);
  CpuBackend backend;
  Progress progress;
  SplatsHandle splats = backend.splats(result.root, progress);
  renderer.uploadSplats(splats->hostData(), splats->count(), splatShapeOf(result.grid, *splats));
  return splats->count();
}

// 200 x 150 pixels looking at the origin from (0, -4, 1), z up.
ViewportFrame sphereFrame() {
  ViewportFrame frame;
  frame.width = 200;
  frame.height = 150;
  frame.eye = glm::dvec3(0.0, -4.0, 1.0);
  frame.forward = glm::normalize(-frame.eye);
  frame.up = glm::dvec3(0.0, 0.0, 1.0);
  frame.viewProjection = glm::perspective(0.8, 200.0 / 150.0, 0.1, 20.0) *
                         glm::lookAt(frame.eye, glm::dvec3(0.0), frame.up);
  return frame;
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
  options.section.startFraction = 0.5;
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

// Points and compute (ui/splat_primitive.h): one vertex per splat, or one compute invocation,
// the disc and its depth found per pixel by casting the pixel's ray onto the splat's plane, look
// as the quads do: the same silhouettes, the same part in front where two overlap, the same
// section caps.
TEST(HeadlessRender, PointsAndComputeLookLikeQuads) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  auto red = std::make_shared<Node>(*test::box(glm::dvec3(1.6, 1.6, 1.6)));
  red->color = glm::vec3(0.9f, 0.15f, 0.1f);
  auto green = std::make_shared<Node>(*test::sphere(0.75, glm::dvec3(0.55, -0.55, 0.55)));
  green->color = glm::vec3(0.1f, 0.8f, 0.2f);
  // Cells of several pixels, where a disc's size and depth show.
  Scene scene = test::makeScene(test::op(NodeKind::Union, {red, green}), 40);
  auto backend = std::make_shared<CpuBackend>();
  SceneRenderOptions options;
  options.width = 240;
  options.height = 180;
  options.grid = false;
  options.everySplat = true;
  Progress progress;
  const bool compute = ViewportRenderer().computeReady();
  for (bool cut : {false, true}) {
    options.section.on = cut;
    options.section.axis = 0;
    options.section.startFraction = 0.6;
    options.splatPrimitive = SplatPrimitive::Quads;
    SceneRender quads = renderScene(scene, "", backend, options, progress);
    EXPECT_FALSE(quads.drawnAsPoints);
    EXPECT_FALSE(quads.drawnByCompute);
    for (SplatPrimitive kind : {SplatPrimitive::Points, SplatPrimitive::Compute}) {
      if (kind == SplatPrimitive::Compute && !compute) continue;
      SCOPED_TRACE(std::string(cut ? "section on, " : "whole, ") +
                   (kind == SplatPrimitive::Points ? "points" : "compute"));
      options.splatPrimitive = kind;
      SceneRender other = renderScene(scene, "", backend, options, progress);
      EXPECT_EQ(other.drawnAsPoints, kind == SplatPrimitive::Points);
      EXPECT_EQ(other.drawnByCompute, kind == SplatPrimitive::Compute);
      int far = 0, covered = 0, greenPixels = 0;
      const Rgb background = pixel(quads, 240, 0, 0);
      for (int y = 0; y < 180; ++y)
        for (int x = 0; x < 240; ++x) {
          Rgb a = pixel(quads, 240, x, y), b = pixel(other, 240, x, y);
          const int d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
          far += d > 24 ? 1 : 0;
          covered += (a.r != background.r || a.g != background.g || a.b != background.b) ? 1 : 0;
          greenPixels += a.g > a.r + 60 ? 1 : 0;
        }
      EXPECT_GT(covered, 8000) << "the parts fill part of the image";
      EXPECT_GT(greenPixels, 1000) << "the sphere shows in front of the box";
      // Mesa draws them alike to the pixel here; discs 1.2 times as wide differ in 145-194
      // pixels of 43,000, the depth of the splat's centre instead of the pixel's in 51-72.
      EXPECT_LT(far, covered / 2000) << "pixels that differ visibly from the quads";
    }
  }
  if (!compute) std::printf("compute not tried: %s\n", ViewportRenderer().computeProblem().c_str());
}

// Automatic: the renderer times its draws and settles on the kind it measured cheaper, after
// trying each (whichever that is on this driver); on a software rasterizer, whose timers miss
// the pixels' work, it draws quads.
TEST(HeadlessRender, AutomaticDrawsTheKindItMeasuredCheaper) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  ASSERT_GT(uploadSphere(renderer), ViewportRenderer::kTimedDrawSplats);
  renderer.limitDetailLevel(0);
  const ViewportFrame frame = sphereFrame();
  RenderTarget target(frame.width, frame.height);
  target.bind();
  if (!renderer.timersTrusted()) {
    // A software rasterizer (CI's Mesa): quads alone, nothing timed as points.
    for (int i = 0; i < 3; ++i) {
      renderer.draw(frame, {}, {}, {});
      glFinish();
    }
    EXPECT_EQ(renderer.pointsDrawn(), 0u);
    EXPECT_GT(renderer.quadsDrawn(), 0u);
    EXPECT_EQ(renderer.nsPerSplat(SplatPrimitive::Points), 0.0);
    renderer.trustTimers(true);  // the choice itself, on whatever times this driver gives
  }
  const bool compute = renderer.computeReady();
  for (int i = 0; i < 6; ++i) {
    renderer.draw(frame, {}, {}, {});
    glFinish();  // the timer's result is there for the next draw
  }
  EXPECT_GT(renderer.nsPerSplat(SplatPrimitive::Points), 0.0);
  EXPECT_GT(renderer.nsPerSplat(SplatPrimitive::Quads), 0.0);
  EXPECT_EQ(renderer.nsPerSplat(SplatPrimitive::Compute) > 0.0, compute);
  EXPECT_GT(renderer.pointsDrawn(), 0u);
  EXPECT_GT(renderer.quadsDrawn(), 0u);
  EXPECT_EQ(renderer.computedDrawn() > 0, compute);
  // From here on each image is drawn as the kind measured cheapest before it, but for a retry
  // of another every kRetryEvery images (not more: an earlier version, once it retried, kept
  // drawing the dearer kind).
  constexpr int kImages = 80;
  int otherKind = 0;
  for (int i = 0; i < kImages; ++i) {
    const size_t before[3] = {renderer.quadsDrawn(), renderer.pointsDrawn(),
                              renderer.computedDrawn()};
    renderer.draw(frame, {}, {}, {});
    glFinish();
    // The times the draw chose by: it reads the last timer's result before it chooses (on a
    // busy machine the kinds' times cross now and then; the times before the draw would then
    // count its right choice as a wrong one).
    const double ns[3] = {renderer.nsPerSplat(SplatPrimitive::Quads),
                          renderer.nsPerSplat(SplatPrimitive::Points),
                          compute ? renderer.nsPerSplat(SplatPrimitive::Compute) : 1e300};
    const size_t after[3] = {renderer.quadsDrawn(), renderer.pointsDrawn(),
                             renderer.computedDrawn()};
    const int cheapest = int(std::min_element(ns, ns + 3) - ns);
    otherKind += after[cheapest] > before[cheapest] ? 0 : 1;
  }
  EXPECT_LE(otherKind, kImages / ViewportRenderer::kRetryEvery + 1);
  target.read();
}

// Views whose images are drawn a share a frame (a coarse image first) still time each kind: a
// kind with no time draws the rest of the image at once, timed, in place of a share. Without
// it, shares went as quads until every kind had a time from a whole image, which such views never
// draw, and Automatic never learnt that another kind was cheaper.
TEST(HeadlessRender, ImagesDrawnAShareAFrameStillTimeEachKind) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  ASSERT_GT(uploadSphere(renderer), 3 * ViewportRenderer::kMinShare);
  renderer.limitDetailLevel(0);
  renderer.trustTimers(true);
  ViewportFrame frame = sphereFrame();
  RenderTarget target(frame.width, frame.height);
  target.bind();
  for (int view = 0; view < 4; ++view) {
    frame.eye = glm::dvec3(0.3 * view, -4.0, 1.0);
    frame.forward = glm::normalize(-frame.eye);
    frame.viewProjection = glm::perspective(0.8, 200.0 / 150.0, 0.1, 20.0) *
                           glm::lookAt(frame.eye, glm::dvec3(0.0), frame.up);
    for (int i = 0; i < 2; ++i) {  // the view moved (a coarse image), then at rest (refined)
      renderer.setFrameShares(ViewportRenderer::kMinShare, ViewportRenderer::kMinShare);
      renderer.drawCached(frame, {}, {}, {}, 100.0);
      // The first moved view is drawn a share at a time (nothing timed yet); later ones may be
      // drawn whole where the times now say they fit the share (on a loaded machine now and
      // then: a CI run saw the fourth drawn whole).
      if (i == 0 && view == 0) {
        EXPECT_TRUE(renderer.showsCoarseImage());
      }
      glFinish();  // the timer's result is there for the next frame
    }
  }
  EXPECT_GT(renderer.nsPerSplat(SplatPrimitive::Points), 0.0);
  EXPECT_GT(renderer.nsPerSplat(SplatPrimitive::Quads), 0.0);
  EXPECT_EQ(renderer.nsPerSplat(SplatPrimitive::Compute) > 0.0, renderer.computeReady());
  target.read();
}

// A moving view draws its whole image, not the coarse one, where the measured time per splat
// says that the whole costs at most half the frame's target, even while the frames' share is
// small (a view in motion never raises it); the coarse image where it would cost more.
TEST(HeadlessRender, AMovingViewIsDrawnWholeWhereTheSplatsTimeSaysItFits) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  for (bool fits : {true, false}) {
    SCOPED_TRACE(fits ? "splats cheap enough" : "splats too dear");
    ViewportRenderer renderer;
    const size_t splats = uploadSphere(renderer);
    ASSERT_GT(splats, 3 * ViewportRenderer::kMinShare);
    renderer.limitDetailLevel(0);
    renderer.trustTimers(true);
    // A whole image at half the frame's target, just within or just beyond.
    const double ns =
        0.5 * ViewportRenderer::kTargetFrameMs * 1e6 / double(splats) * (fits ? 0.9 : 1.1);
    for (SplatPrimitive kind :
         {SplatPrimitive::Quads, SplatPrimitive::Points, SplatPrimitive::Compute})
      renderer.assumeNsPerSplat(kind, ns);
    renderer.setFrameShares(ViewportRenderer::kMinShare, ViewportRenderer::kMinShare);
    ViewportFrame frame = sphereFrame();
    RenderTarget target(frame.width, frame.height);
    target.bind();
    for (int i = 0; i < 3; ++i) {  // the camera turning a little each frame
      frame.eye = glm::dvec3(0.3 * i, -4.0, 1.0);
      frame.forward = glm::normalize(-frame.eye);
      frame.viewProjection = glm::perspective(0.8, 200.0 / 150.0, 0.1, 20.0) *
                             glm::lookAt(frame.eye, glm::dvec3(0.0), frame.up);
      renderer.drawCached(frame, {}, {}, {}, 30.0);
      EXPECT_EQ(renderer.showsCoarseImage(), !fits) << "frame " << i;
    }
    target.read();
  }
}

// Close up, the sphere runs off the image's edges: points whose centres lie just outside the view
// still draw their visible part (GL may clip a point by its vertex; the renderer widens the
// viewport for points and shrinks the projection to match), so the edges look as the quads draw
// them. Mesa draws such points anyway; here the test holds the widened mapping to the pixel (a
// projection left unshrunk differs in 588 of 2064 edge pixels), on drivers that clip the edges.
TEST(HeadlessRender, PointsReachTheImagesEdges) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  uploadSphere(renderer);
  renderer.limitDetailLevel(0);
  ViewportFrame frame = sphereFrame();
  frame.eye = glm::dvec3(0.0, -1.9, 0.3);
  frame.forward = glm::normalize(-frame.eye);
  frame.viewProjection = glm::perspective(0.8, 200.0 / 150.0, 0.1, 20.0) *
                         glm::lookAt(frame.eye, glm::dvec3(0.0), frame.up);
  std::vector<uint8_t> images[2];
  for (int points = 0; points < 2; ++points) {
    renderer.setSplatPrimitive(points ? SplatPrimitive::Points : SplatPrimitive::Quads);
    const size_t before = renderer.pointsDrawn();
    RenderTarget target(frame.width, frame.height);
    target.bind();
    renderer.draw(frame, {}, {}, {});
    EXPECT_EQ(renderer.pointsDrawn() > before, points == 1);
    images[points] = target.read();
  }
  int edge = 0, differing = 0;
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      if (x > 2 && y > 2 && x < frame.width - 3 && y < frame.height - 3) continue;
      ++edge;
      const size_t i = (size_t(y) * size_t(frame.width) + size_t(x)) * 4;
      int d = 0;
      for (int c = 0; c < 3; ++c)
        d = std::max(d, std::abs(int(images[0][i + c]) - int(images[1][i + c])));
      differing += d > 24 ? 1 : 0;
    }
  EXPECT_LT(differing, edge / 50) << "of the " << edge << " pixels along the edges";
}

// The coarse image of a view that changed (every k-th splat at half resolution) keeps k within
// the driver's largest attribute stride (2048 bytes: 102 splats) by sampling a coarser level:
// with a share of 200 splats a frame, a sphere of some 33,000 splats would need k = 167, which
// GL refuses (the draw then read whatever the last pointers gave, and a driver crashed on it).
// No GL error, and the coarse image covers what the full one does.
TEST(HeadlessRender, CoarseImageCoversTheViewWhenTheShareIsSmall) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  ASSERT_GT(uploadSphere(renderer), 30000u);
  const ViewportFrame frame = sphereFrame();
  RenderTarget full(frame.width, frame.height);
  full.bind();
  renderer.draw(frame, {}, {}, {});
  const std::vector<uint8_t> fullPixels = full.read();
  renderer.setFrameShares(200, 200);
  renderer.limitDetailLevel(0);  // the view's level: every splat (the sphere is a few pixels)
  RenderTarget window(frame.width, frame.height);
  window.bind();
  while (glGetError() != GL_NO_ERROR) {
  }
  renderer.drawCached(frame, {}, {}, {}, 16.0);
  ASSERT_TRUE(renderer.showsCoarseImage());
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "a refused stride (GL_INVALID_VALUE)";
  const std::vector<uint8_t> coarsePixels = window.read();
  auto background = [](const std::vector<uint8_t>& p, size_t i) {
    return std::abs(int(p[i * 4 + 0]) - int(p[i * 4 + 2])) < 12 && p[i * 4 + 0] < 90;
  };
  int sphere = 0, missed = 0;
  for (size_t i = 0; i < size_t(frame.width) * size_t(frame.height); ++i) {
    if (background(fullPixels, i)) continue;
    ++sphere;
    missed += background(coarsePixels, i) ? 1 : 0;
  }
  EXPECT_GT(sphere, 4000);
  EXPECT_LT(missed, sphere / 20) << "of the sphere's pixels the coarse image left empty";
}

// The coarse image of a moving view turns to a quarter resolution when a frame at the fewest
// splats still takes longer than the target (its cost is then the pixels filled, as under a
// software GL driver), and back to half only when frames take less than a quarter of the target
// (a half image, four times the pixels, would fit); a frame over the target with splats still to
// shed keeps half (fewer splats are the cheaper fix).
TEST(HeadlessRender, CoarseImageTurnsToAQuarterWhenFillBound) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  ASSERT_GT(uploadSphere(renderer), 30000u);
  renderer.limitDetailLevel(0);
  RenderTarget window(200, 150);
  window.bind();
  int turn = 0;
  // Each frame turns the camera, so each draws the coarse image of a moved view.
  auto movedFrame = [&](double lastFrameMs) {
    ViewportFrame frame = sphereFrame();
    const double angle = 0.05 * double(++turn);
    frame.eye = glm::dvec3(4.0 * std::sin(angle), -4.0 * std::cos(angle), 1.0);
    frame.forward = glm::normalize(-frame.eye);
    frame.viewProjection = glm::perspective(0.8, 200.0 / 150.0, 0.1, 20.0) *
                           glm::lookAt(frame.eye, glm::dvec3(0.0), frame.up);
    renderer.drawCached(frame, {}, {}, {}, lastFrameMs);
    EXPECT_TRUE(renderer.showsCoarseImage());
  };
  // A first frame takes the upload's time off its own (untimed here).
  movedFrame(ViewportRenderer::kTargetFrameMs);
  // Slow frames with a large share: the share shrinks, the image stays at half.
  renderer.setFrameShares(20000, 200);
  movedFrame(10.0);
  movedFrame(30.0);
  EXPECT_EQ(renderer.coarseShrink(), 2);
  EXPECT_LT(renderer.splatsPerFrame(), 20000u);
  // Slow frames shed splats down to the fewest; slow there: a quarter, and it stays while frames
  // are near the target.
  for (int i = 0; i < 8; ++i) movedFrame(30.0);
  EXPECT_EQ(renderer.splatsPerFrame(), ViewportRenderer::kMinShare);
  EXPECT_EQ(renderer.coarseShrink(), 4);
  movedFrame(11.0);
  EXPECT_EQ(renderer.coarseShrink(), 4);
  movedFrame(0.4 * ViewportRenderer::kTargetFrameMs);  // quick, but a half would not fit
  EXPECT_EQ(renderer.coarseShrink(), 4);
  // Frames so quick that four times the pixels fit: back to half.
  movedFrame(0.2 * ViewportRenderer::kTargetFrameMs);
  EXPECT_EQ(renderer.coarseShrink(), 2);
}

// The window shows drawCached's complete image only after the frame that drew it whole, for
// exactly that view, content, lines and overlay: a moved camera, new splats, another overlay or
// a draw by other means (a screenshot) each make the view be drawn again.
TEST(HeadlessRender, TheWindowShowsACompleteImageUntilSomethingInItChanges) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  uploadSphere(renderer);
  renderer.setFrameShares(1 << 22, 1 << 22);  // every splat in one frame
  RenderTarget window(200, 150);
  window.bind();
  const ViewportFrame frame = sphereFrame();
  const std::vector<LineVertex> none;
  EXPECT_FALSE(renderer.windowShows(frame, none, none, none)) << "nothing drawn yet";
  renderer.drawCached(frame, none, none, none, 16.0);
  ASSERT_FALSE(renderer.refining());
  EXPECT_TRUE(renderer.windowShows(frame, none, none, none));
  renderer.skipFrame(16.0);
  EXPECT_TRUE(renderer.windowShows(frame, none, none, none)) << "a skipped frame changes nothing";

  ViewportFrame moved = frame;
  moved.eye.x += 0.01;
  EXPECT_FALSE(renderer.windowShows(moved, none, none, none)) << "the camera moved";
  ViewportFrame shifted = frame;
  shifted.x += 1;
  EXPECT_FALSE(renderer.windowShows(shifted, none, none, none)) << "the view moved in the window";
  const std::vector<LineVertex> gizmo = {lineVertex(glm::dvec3(0.0), glm::vec4(1.0f)),
                                         lineVertex(glm::dvec3(1.0), glm::vec4(1.0f))};
  EXPECT_FALSE(renderer.windowShows(frame, none, gizmo, none)) << "another overlay";
  EXPECT_FALSE(renderer.windowShows(frame, none, none, gizmo)) << "other overlay triangles";
  EXPECT_FALSE(renderer.windowShows(frame, gizmo, none, none)) << "other lines";

  renderer.draw(frame, none, none, none);
  EXPECT_FALSE(renderer.windowShows(frame, none, none, none)) << "drawn by other means";
  renderer.drawCached(frame, none, none, none, 16.0);
  EXPECT_TRUE(renderer.windowShows(frame, none, none, none));
  renderer.setLeafStyles(LeafStyleTable{{glm::vec3(0.9f, 0.1f, 0.1f)}, {1}});
  EXPECT_FALSE(renderer.windowShows(frame, none, none, none)) << "other colours or selection";
  renderer.drawCached(frame, none, none, none, 16.0);
  EXPECT_TRUE(renderer.windowShows(frame, none, none, none));
  uploadSphere(renderer);
  EXPECT_FALSE(renderer.windowShows(frame, none, none, none)) << "new splats";
}

// A kept view drawn again within a rectangle (where a panel that changed reaches it) gets there
// the pixels the whole view had, with its overlay, and leaves every other pixel alone.
TEST(HeadlessRender, AKeptViewRepaintsExactlyWithinTheRectangleGiven) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  uploadSphere(renderer);
  renderer.setFrameShares(1 << 22, 1 << 22);
  const int width = 260, height = 190;
  RenderTarget window(width, height);
  window.bind();
  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ViewportFrame frame = sphereFrame();  // 200 x 150
  frame.x = 40;
  frame.y = 25;
  const std::vector<LineVertex> none;
  const std::vector<LineVertex> overlay = {lineVertex(glm::dvec3(-1.2, 0.0, -0.8), glm::vec4(1.0f)),
                                           lineVertex(glm::dvec3(1.2, 0.0, 0.8), glm::vec4(1.0f))};
  renderer.drawCached(frame, none, overlay, none, 16.0);
  ASSERT_TRUE(renderer.windowShows(frame, none, overlay, none));
  const std::vector<uint8_t> whole = window.read();
  // Something else over everything (a panel's background), then the view repainted in part.
  window.bind();
  glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const PixelRect clip{20, 60, 150, 120};  // reaches out of the view on the left
  renderer.repaintWindow(frame, overlay, none, clip);
  const std::vector<uint8_t> after = window.read();
  const PixelRect inside =
      clip.intersect({frame.x, frame.y, frame.x + frame.width, frame.y + frame.height});
  size_t wrongInside = 0, touchedOutside = 0, differsFromMarker = 0;
  for (int row = 0; row < height; ++row)  // read() gives the top row first; GL counts from below
    for (int x = 0; x < width; ++x) {
      const int y = height - 1 - row;
      const size_t i = (size_t(row) * width + size_t(x)) * 4;
      const bool in = x >= inside.x0 && x < inside.x1 && y >= inside.y0 && y < inside.y1;
      const bool marker = after[i] == 255 && after[i + 1] == 0 && after[i + 2] == 255;
      if (in) {
        wrongInside +=
            after[i] != whole[i] || after[i + 1] != whole[i + 1] || after[i + 2] != whole[i + 2];
        differsFromMarker += marker ? 0 : 1;
      } else {
        touchedOutside += marker ? 0 : 1;
      }
    }
  EXPECT_EQ(wrongInside, 0u) << "pixels of the repainted rectangle unlike the whole view's";
  EXPECT_EQ(touchedOutside, 0u) << "pixels outside the rectangle (or the view) drawn";
  EXPECT_GT(differsFromMarker, size_t(inside.area()) / 2) << "the repaint drew nothing";
  EXPECT_FALSE(glIsEnabled(GL_SCISSOR_TEST));
}

// The splats of a sphere of `radius` at `cells` cells moved by `shift`, as a ghost carries them;
// *h: their lattice's cell size.
std::vector<Splat> ghostSphere(double radius, int cells, const glm::vec3& shift, double* h) {
  Scene scene = test::makeScene(test::sphere(radius), cells);
  EvalResult result = test::evaluateCpu(scene);
  CpuBackend backend;
  Progress progress;
  SplatsHandle splats = backend.splats(result.root, progress);
  std::vector<Splat> out(splats->hostData(), splats->hostData() + splats->count());
  for (Splat& s : out)
    for (int k = 0; k < 3; ++k) s.position[k] += shift[k];
  *h = result.grid.h;
  return out;
}

// Ghosts of one layer made on different lattices (a ghost carried from a coarse pass beside one
// of a fine pass) are each drawn with their own lattice's splat size: the coarse one whole, the
// fine one not grown by the coarse one's splats (the whole layer was drawn at the coarsest).
TEST(HeadlessRender, EachGhostIsDrawnWithItsOwnLatticesSplats) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  double fineH = 0.0, coarseH = 0.0;
  const std::vector<Splat> fine = ghostSphere(0.5, 128, glm::vec3(-1.0f, 0.0f, 0.0f), &fineH);
  const std::vector<Splat> coarse = ghostSphere(0.5, 8, glm::vec3(1.0f, 0.0f, 0.0f), &coarseH);
  ASSERT_GT(coarseH, 8.0 * fineH);
  std::vector<Splat> both = fine;
  both.insert(both.end(), coarse.begin(), coarse.end());
  const ViewportFrame frame = sphereFrame();  // 200 x 150; x < 0 left of the middle
  const std::vector<LineVertex> none;
  // The tinted pixels left and right of the middle, with the layer's runs as given.
  struct Tinted {
    int left = 0, right = 0;
  };
  const auto render = [&](const std::vector<ViewportRenderer::GhostRun>& runs) {
    ViewportRenderer renderer;
    RenderTarget target(frame.width, frame.height);
    target.bind();
    const std::vector<uint8_t> plain = [&] {
      renderer.draw(frame, none, none, none);
      return target.read();
    }();
    const std::vector<ViewportRenderer::GhostRun> layers[2] = {runs, {}};
    renderer.setGhosts(both, {}, layers);
    target.bind();
    renderer.draw(frame, none, none, none);
    const std::vector<uint8_t> ghosted = target.read();
    Tinted t;
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) {
        const size_t i = (size_t(y) * size_t(frame.width) + size_t(x)) * 4;
        const bool tinted = std::abs(int(ghosted[i]) - int(plain[i])) > 8;
        (x < frame.width / 2 ? t.left : t.right) += tinted ? 1 : 0;
      }
    return t;
  };
  const Tinted own = render({{fine.size(), fineH}, {coarse.size(), coarseH}});
  const Tinted coarsest = render({{both.size(), coarseH}});
  const Tinted finest = render({{both.size(), fineH}});
  // The fine ghost as its own splats draw it, not grown by a coarse lattice's.
  EXPECT_GT(own.left, 500) << "the fine ghost is drawn";
  EXPECT_LT(std::abs(own.left - finest.left), own.left / 50) << own.left << " " << finest.left;
  EXPECT_GT(coarsest.left, own.left + own.left / 10)
      << "drawn at the coarse size the fine ghost grows: " << coarsest.left << " " << own.left;
  // The coarse ghost whole, as at its size, where the fine size leaves it in scattered dots.
  EXPECT_EQ(own.right, coarsest.right);
  EXPECT_LT(finest.right, own.right / 2) << finest.right << " " << own.right;
}

}  // namespace
}  // namespace strata::ui

namespace strata::ui {
namespace {

// The same parts at a finer resolution (the preview's resolution raised) with too many splats
// for a frame: the complete image shown stays, pixel for pixel, while the new one is drawn, and
// is replaced once that is complete. Without the hold, a first or coarse image of the new
// splats shows them worse meanwhile (an artist saw it for seconds).
TEST(HeadlessRender, AFinerSamplingOfTheSamePartsKeepsTheImageShownUntilItsOwnIsDrawn) {
  std::string why;
  auto gl = headlessOrSkipReason(&why);
  if (!gl) GTEST_SKIP() << why;
  ViewportRenderer renderer;
  renderer.trustTimers(false);
  uploadSphere(renderer, 64);
  const ViewportFrame frame = sphereFrame();
  RenderTarget window(frame.width, frame.height);
  auto drawFrame = [&] {
    window.bind();
    renderer.drawCached(frame, {}, {}, {}, 100.0);
    glFinish();
    return window.read();
  };
  renderer.setFrameShares(size_t(1) << 30, size_t(1) << 30);
  const std::vector<uint8_t> before = drawFrame();
  ASSERT_FALSE(renderer.refining());
  for (const bool hold : {true, false}) {
    renderer.setFrameShares(ViewportRenderer::kMinShare, ViewportRenderer::kMinShare);
    if (hold) renderer.holdShownImage();
    const size_t finer = uploadSphere(renderer, hold ? 256 : 192);
    ASSERT_GT(finer, 3 * ViewportRenderer::kMinShare);
    const std::vector<uint8_t> first = drawFrame();
    EXPECT_TRUE(renderer.refining());
    if (hold) {
      EXPECT_FALSE(renderer.showsCoarseImage());
      EXPECT_TRUE(first == before) << "the image shown stays";
    } else {
      EXPECT_FALSE(first == before) << "a first or coarse image of the new splats";
    }
    for (int i = 0; i < 1000 && renderer.refining(); ++i) drawFrame();
    EXPECT_FALSE(renderer.refining()) << "the new image is drawn and shown";
    if (hold) {
      // Back to the coarser sampling for the run without the hold, its image complete.
      renderer.setFrameShares(size_t(1) << 30, size_t(1) << 30);
      uploadSphere(renderer, 64);
      EXPECT_TRUE(drawFrame() == before);
    }
  }
}

}  // namespace
}  // namespace strata::ui
