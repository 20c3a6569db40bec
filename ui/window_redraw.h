// What a frame of the editor's window redraws: where the window keeps its back buffer between
// frames (GlWindow::presentsParts: a software rasteriser), only the 3D view's rectangle and the
// rectangles of the Dear ImGui draw lists that changed since the last frame, then only those
// are sent to the screen; elsewhere, everything.
//
// Why: under Mesa llvmpipe every pixel drawn or sent costs (about 2-3 ns here, a 1600 x 1000
// window's copy 4-5 ms), and the panels, redrawn every frame though they rarely change, were
// 5-9 ms of a 16-25 ms frame while the engine works (`strata edit --measure-frames`). The
// pixels are those of drawing everything: within each redrawn rectangle, the background, the
// view and every list that reaches it, in order; the rest is what the last frame left.
//
// What the promise rests on: the caller draws every pixel of the view's rectangle (opaque) in
// each frame that does not keep it (a kept view shows what it showed); a texture's contents
// never change under the same ImTextureID (the font atlas is uploaded once); user callbacks in the
// draw lists draw only within the scissor box they are given (their lists count as covering the
// whole window).
//
// Threads: the UI thread, with the window's GL context current.
#pragma once

#include <imgui.h>

#include <cstdint>
#include <string>
#include <vector>

#include "ui/panel_renderer.h"
#include "ui/pixel_rect.h"

namespace strata::ui {

// One ImGui draw list as a frame drew it: what it drew (compared with the next frame's list at
// the same position) and the pixels it may have touched.
struct DrawListRecord {
  std::string owner;
  PixelRect rect;
  std::vector<ImDrawVert> vertices;
  std::vector<ImDrawIdx> indices;
  struct Command {
    ImVec4 clip;
    ImTextureID texture;
    unsigned vertexOffset, indexOffset, elements;
    ImDrawCallback callback;
    void* callbackData;
  };
  std::vector<Command> commands;
  bool sameDrawing(const DrawListRecord& o) const;
};

// The record of `list` in a framebuffer `width` x `height` pixels: its rectangle bounds the
// pixels it can touch (each command's scissor box cut to the vertices' pixel bounds; a user
// callback: the whole framebuffer).
DrawListRecord recordDrawList(const ImDrawList& list, const ImDrawData& data, int width,
                              int height);

// The rectangles an image holding the `previous` frame's lists must redraw to show the
// `current` frame's: `always` (the view), and the old and the new rectangle of each list that
// differs from the list at its position in the previous frame (or has none there), made
// pairwise disjoint (each pixel is in at most one, so nothing is drawn twice over itself).
std::vector<PixelRect> damagedRects(const std::vector<DrawListRecord>& previous,
                                    const std::vector<DrawListRecord>& current,
                                    const PixelRect& always);

// `rects` as pairwise disjoint rectangles covering the same pixels.
std::vector<PixelRect> disjointRects(const std::vector<PixelRect>& rects);

class WindowRedraw {
 public:
  // `keepsBackBuffer`: the window's back buffer holds the last frame's pixels at each begin.
  explicit WindowRedraw(bool keepsBackBuffer) : keeps_(keepsBackBuffer) {}

  // Chooses what this frame redraws in the window's back buffer (width x height pixels, bound
  // for drawing on return): `view` (unless kept), and what damagedRects finds in `data` (after
  // ImGui::Render), or everything where the back buffer is not kept (or after invalidate, a
  // resize). Clears the chosen rectangles outside `view` to kWindowBackground (inside it too
  // where the view is kept). The caller then draws the whole view into `view` (a kept view:
  // within viewRepaints only), calls drawPanels and presents rects().
  // `viewUnchanged`: the view would draw the pixels it drew last (ViewportRenderer::windowShows);
  // where the back buffer is kept, the view is then kept (viewKept): not drawn and not
  // presented, except within viewRepaints, where changed panels reach it (a popup closed over
  // it, a panel's edge): there the caller draws the view again (ViewportRenderer::repaintWindow)
  // before drawPanels.
  void begin(const ImDrawData& data, int width, int height, const PixelRect& view,
             bool viewUnchanged = false);
  // This frame keeps the view's pixels as the last frame left them, but for viewRepaints.
  bool viewKept() const { return viewKept_; }
  // Where a kept view must be drawn again (within the view, pairwise disjoint).
  const std::vector<PixelRect>& viewRepaints() const { return viewRepaints_; }
  // Draws `data`'s lists (the same as given to begin) within the chosen rectangles.
  void drawPanels(PanelRenderer& renderer, const ImDrawData& data) const;
  // The rectangles this frame redrew (pairwise disjoint), to present.
  const std::vector<PixelRect>& rects() const { return rects_; }
  // The next begin redraws everything (the back buffer was drawn another way, or the window
  // lost its pixels).
  void invalidate() { records_.clear(), all_ = true; }
  // The pixels the last begin chose to redraw.
  long long pixelsRedrawn() const;

 private:
  bool keeps_;
  bool all_ = true;
  int width_ = 0, height_ = 0;
  std::vector<DrawListRecord> records_;
  std::vector<PixelRect> rects_;
  bool whole_ = true;  // this frame redraws the whole window: the panels drawn once, whole
  bool viewKept_ = false;
  std::vector<PixelRect> viewRepaints_;
};

// The window's colour where neither the view nor a panel draws (also a capture's clear).
constexpr float kWindowBackground[4] = {0.09f, 0.095f, 0.105f, 1.0f};

}  // namespace strata::ui
