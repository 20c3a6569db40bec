// What a frame redraws (ui/window_redraw.h): the damage rules on their own, and, in a real GL
// context, that frames redrawing only what changed leave the same pixels as drawing everything.
#include <gtest/gtest.h>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "ui/editor.h"
#include "ui/gl_window.h"
#include "ui/panel_renderer.h"
#include "ui/viewport_renderer.h"
#include "ui/window_redraw.h"

namespace strata::ui {
namespace {

// How many rectangles cover each pixel of a w x h grid.
std::vector<int> coverage(const std::vector<PixelRect>& rects, int w, int h) {
  std::vector<int> n(size_t(w) * size_t(h), 0);
  for (const PixelRect& r : rects)
    for (int y = std::max(0, r.y0); y < std::min(h, r.y1); ++y)
      for (int x = std::max(0, r.x0); x < std::min(w, r.x1); ++x)
        ++n[size_t(y) * size_t(w) + size_t(x)];
  return n;
}

// Which pixels of a w x h grid some rectangle covers.
std::vector<bool> covered(const std::vector<PixelRect>& rects, int w, int h) {
  std::vector<bool> c;
  for (int n : coverage(rects, w, h)) c.push_back(n > 0);
  return c;
}

// Damage as drawn: pairwise disjoint, and covering exactly `expected`.
void expectDamage(const std::vector<PixelRect>& damage, const std::vector<PixelRect>& expected) {
  for (int n : coverage(damage, 300, 110)) ASSERT_LE(n, 1);
  EXPECT_EQ(covered(damage, 300, 110), covered(expected, 300, 110));
}

TEST(WindowRedraw, DisjointRectsCoverTheSamePixelsOnceEach) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> at(0, 40);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<PixelRect> rects;
    for (int k = 0; k < 1 + trial % 7; ++k) {
      const int x0 = at(random), y0 = at(random);
      rects.push_back({x0, y0, x0 + at(random) / 2, y0 + at(random) / 2});  // some empty
    }
    const std::vector<PixelRect> disjoint = disjointRects(rects);
    const std::vector<int> before = coverage(rects, 64, 64), after = coverage(disjoint, 64, 64);
    for (size_t i = 0; i < before.size(); ++i) ASSERT_EQ(after[i], before[i] > 0 ? 1 : 0) << i;
    for (const PixelRect& r : disjoint) EXPECT_FALSE(r.empty());
    // The first non-empty rectangle stays whole (the view: its clear is skipped by identity).
    for (const PixelRect& r : rects)
      if (!r.empty()) {
        EXPECT_TRUE(disjoint.front() == r);
        break;
      }
  }
}

DrawListRecord record(const char* owner, PixelRect rect, float firstX) {
  DrawListRecord r;
  r.owner = owner;
  r.rect = rect;
  ImDrawVert v{};
  v.pos = ImVec2(firstX, 0.0f);
  r.vertices.push_back(v);
  return r;
}

TEST(WindowRedraw, DamageIsTheViewAndTheOldAndNewPlaceOfWhatChanged) {
  const PixelRect view{100, 0, 200, 100};
  const std::vector<DrawListRecord> before = {record("left", {0, 0, 100, 100}, 1.0f),
                                              record("right", {200, 0, 300, 100}, 2.0f),
                                              record("menu", {0, 100, 300, 110}, 3.0f)};
  // Nothing changed: the view alone.
  std::vector<PixelRect> d = damagedRects(before, before, view);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_TRUE(d[0] == view);
  // "right" drew something else: its rectangle too.
  std::vector<DrawListRecord> after = before;
  after[1].vertices[0].pos.x = 5.0f;
  expectDamage(damagedRects(before, after, view), {view, {200, 0, 300, 100}});
  // "menu" moved down: where it was and where it is.
  after = before;
  after[2].rect = {0, 90, 300, 100};
  expectDamage(damagedRects(before, after, view), {view, {0, 100, 300, 110}, {0, 90, 300, 100}});
  // A list gone (a closed popup): its old rectangle.
  after = before;
  after.pop_back();
  expectDamage(damagedRects(before, after, view), {view, {0, 100, 300, 110}});
}

// One frame of panels: a left panel whose text changes every other frame, a right panel that
// never changes, a popup that moves from the view over the right panel and is then closed,
// a text over the view.
void buildPanels(int frame, int width, int height) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(width), float(height));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(160, float(height)));
  ImGui::Begin("left", nullptr, ImGuiWindowFlags_NoDecoration);
  ImGui::Text("frame %d", frame / 2);
  ImGui::Button("a button");
  ImGui::End();
  ImGui::SetNextWindowPos(ImVec2(float(width - 120), 0));
  ImGui::SetNextWindowSize(ImVec2(120, float(height)));
  ImGui::Begin("right", nullptr, ImGuiWindowFlags_NoDecoration);
  ImGui::Text("still");
  ImGui::End();
  if (frame < 11) {  // moving from the view over the unchanged right panel, then closed
    ImGui::SetNextWindowPos(ImVec2(330.0f + 6.0f * float(frame), 40.0f + 5.0f * float(frame)));
    ImGui::Begin("over", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Text("over the view %d", frame);
    ImGui::End();
  }
  ImGui::GetForegroundDrawList()->AddText(ImVec2(200, 200), IM_COL32(255, 220, 120, 255),
                                          "a hint on the view");
  // Unchanged, on the view, where the popup passes over it.
  ImGui::GetForegroundDrawList()->AddText(ImVec2(335, 62), IM_COL32(120, 220, 255, 255), "note");
  ImGui::Render();
}

// The view: a colour that changes every frame, filling its rectangle.
void drawView(const PixelRect& view, int frame) {
  glEnable(GL_SCISSOR_TEST);
  glScissor(view.x0, view.y0, view.x1 - view.x0, view.y1 - view.y0);
  glClearColor(0.2f + 0.1f * float(frame % 5), 0.3f, 0.5f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
}

// The pixels (RGB) where the window's back buffer differs from the current ImGui frame drawn
// whole over the view of `frame`, into an image of its own.
size_t pixelsDifferingFromAFullDraw(PanelRenderer& panels, int width, int height,
                                    const PixelRect& view, int frame) {
  glFinish();
  const std::vector<uint8_t> kept = readWindowPixels(width, height);
  RenderTarget whole(width, height);
  whole.bind();
  glViewport(0, 0, width, height);
  glClearColor(kWindowBackground[0], kWindowBackground[1], kWindowBackground[2],
               kWindowBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  drawView(view, frame);
  panels.draw(*ImGui::GetDrawData(), width, height, {0, 0, width, height});
  const std::vector<uint8_t> full = whole.read();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (kept.size() != full.size()) return kept.size() / 4;
  size_t differ = 0;
  for (size_t i = 0; i < kept.size(); i += 4)
    differ += kept[i] != full[i] || kept[i + 1] != full[i + 1] || kept[i + 2] != full[i + 2];
  return differ;
}

TEST(WindowRedraw, FramesThatRedrawOnlyWhatChangedShowWhatAFullDrawShows) {
  std::string why;
  if (!editorDisplayAvailable(&why)) GTEST_SKIP() << "no display: " << why;
  const int width = 480, height = 320;
  setenv("STRATA_MSAA", "0", 1);  // compared with a single-sampled image, pixel for pixel
  GlWindow window(width, height, "window redraw test", false);
  unsetenv("STRATA_MSAA");
  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window.handle(), &fbWidth, &fbHeight);
  ASSERT_EQ(fbWidth, width);
  ASSERT_EQ(fbHeight, height);
  ImGuiContext* context = ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  {
    PanelRenderer panels;
    WindowRedraw redraw(true);  // never swapped here: the back buffer keeps its pixels
    const PixelRect view{160, 0, width - 120, height};
    long long viewOnly = 0;
    for (int frame = 0; frame < 12; ++frame) {
      buildPanels(frame, width, height);
      redraw.begin(*ImGui::GetDrawData(), width, height, view);
      drawView(view, frame);
      redraw.drawPanels(panels, *ImGui::GetDrawData());
      if (frame % 2 == 1 && frame > 2) viewOnly = std::max(viewOnly, redraw.pixelsRedrawn());
    }
    EXPECT_EQ(pixelsDifferingFromAFullDraw(panels, width, height, view, 11), 0u);
    // Frames where the left panel kept its text redrew the view, the popup's old and new place
    // and the hint: well under the whole window.
    EXPECT_GT(viewOnly, 0);
    EXPECT_LT(viewOnly, (long long)(width)*height * 3 / 4);
  }
  ImGui::DestroyContext(context);
}

// A frame whose view would draw what the window shows keeps the view's pixels and does not
// send them (a panel changed, not the view), but where a changed panel reaches the view (a popup
// moving over it, a panel's edge): there the view is drawn again. The pixels stay those of a
// full draw.
TEST(WindowRedraw, AnUnchangedViewIsKeptButWhereChangedPanelsReachIt) {
  std::string why;
  if (!editorDisplayAvailable(&why)) GTEST_SKIP() << "no display: " << why;
  const int width = 480, height = 320;
  setenv("STRATA_MSAA", "0", 1);
  GlWindow window(width, height, "window redraw test", false);
  unsetenv("STRATA_MSAA");
  ImGuiContext* context = ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  {
    PanelRenderer panels;
    WindowRedraw redraw(true);
    const PixelRect view{160, 30, width - 120, height - 20};
    const int still = 3;  // the view's last change
    for (int frame = 0; frame < 16; ++frame) {
      buildPanels(frame, width, height);
      // Frame 9 follows an exposure (or a resize): everything is drawn, the view too.
      if (frame == 9) redraw.invalidate();
      redraw.begin(*ImGui::GetDrawData(), width, height, view, frame > still);
      EXPECT_EQ(redraw.viewKept(), frame > still && frame != 9) << "frame " << frame;
      long long repainted = 0;
      for (const PixelRect& r : redraw.viewRepaints()) {
        EXPECT_TRUE(r.intersect(view) == r) << "a repaint outside the view";
        repainted += r.area();
      }
      if (frame == 4) {
        EXPECT_GT(repainted, 0) << "the popup moved over the view";
      }
      if (frame >= 13) {
        // Only the left panel changes (every other frame), beside the view: its pixels and at
        // most a sliver of the view along its edge, where the whole view was redrawn before.
        EXPECT_LE(redraw.pixelsRedrawn(), 160LL * height + 2LL * height) << "frame " << frame;
        EXPECT_LT(repainted, view.area() / 20) << "frame " << frame;
      }
      if (!redraw.viewKept()) {
        drawView(view, std::min(frame, still));
      } else {
        for (const PixelRect& r : redraw.viewRepaints()) drawView(r, still);
      }
      redraw.drawPanels(panels, *ImGui::GetDrawData());
    }
    EXPECT_EQ(pixelsDifferingFromAFullDraw(panels, width, height, view, still), 0u);
  }
  ImGui::DestroyContext(context);
}

// Where parts are presented, the driver resizes the back buffer only at a swap: a window made
// larger once ended the process (an X error copying beyond the old buffer), a smaller one showed
// its frames shifted. Frames over a series of sizes must present without error and leave the
// pixels of a full draw at the last size.
TEST(WindowRedraw, AResizedWindowPresentsWholeFramesOfItsNewSize) {
  std::string why;
  if (!editorDisplayAvailable(&why)) GTEST_SKIP() << "no display: " << why;
  setenv("STRATA_MSAA", "0", 1);  // partial presents need a single-sampled window
  GlWindow window(400, 300, "window resize test", false);
  unsetenv("STRATA_MSAA");
  if (!window.presentsParts())
    GTEST_SKIP() << "this driver offers no partial presents (" << window.description() << ")";
  ImGuiContext* context = ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  {
    PanelRenderer panels;
    WindowRedraw redraw(true);
    int width = 0, height = 0, frame = 0;
    for (const auto& size : {std::pair{400, 300}, {560, 380}, {320, 240}, {640, 420}}) {
      glfwSetWindowSize(window.handle(), size.first, size.second);
      for (int wait = 0; wait < 100; ++wait) {
        glfwPollEvents();
        glfwGetFramebufferSize(window.handle(), &width, &height);
        if (width == size.first && height == size.second) break;
        glfwWaitEventsTimeout(0.01);
      }
      ASSERT_EQ(width, size.first);
      ASSERT_EQ(height, size.second);
      for (int k = 0; k < 3; ++k, ++frame) {
        buildPanels(frame, width, height);
        const PixelRect view{160, 0, width - 120, height};
        redraw.begin(*ImGui::GetDrawData(), width, height, view);
        drawView(view, frame);
        redraw.drawPanels(panels, *ImGui::GetDrawData());
        if (!window.present(redraw.rects(), width, height)) redraw.invalidate();
      }
    }
    EXPECT_EQ(pixelsDifferingFromAFullDraw(panels, width, height, {160, 0, width - 120, height},
                                           frame - 1),
              0u)
        << "at " << width << " x " << height;
  }
  ImGui::DestroyContext(context);
}

}  // namespace
}  // namespace strata::ui
