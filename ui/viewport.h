// The 3D view in the middle of the editor: camera navigation, click-to-select, the gizmo, and
// drawing the scene through ViewportRenderer.
//
// Navigation: orbit with the middle mouse button (or Alt + left), pan with Shift + middle, zoom
// with the wheel; F frames the selection, Home shows everything, 1 / 3 / 7 look from the front,
// right, top (Ctrl: back, left, bottom), 5 toggles orthographic; W / E / R pick move, rotate,
// scale. Input is taken only when ImGui does not want it.
//
// Threads: the UI thread.
#pragma once

#include <optional>

#include "ui/camera.h"
#include "ui/editor_state.h"
#include "ui/gizmo.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

// A rectangle of the window in window coordinates (ImGui's: pixels, origin top-left).
struct ViewRect {
  double x = 0.0, y = 0.0, width = 1.0, height = 1.0;
};

class Viewport {
 public:
  Camera camera;

  void handleInput(EditorState& state, const ViewRect& rect);
  // Draws into the bound framebuffer of `framebufferHeight` pixels, `pixelScale` framebuffer
  // pixels per window pixel.
  void draw(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
            int framebufferHeight, double pixelScale);
  // Frame the whole scene / the selection (at the next handleInput or draw).
  void viewAll(const EditorState& state);
  void frameSelected(const EditorState& state);
  bool gizmoDragging() const { return gizmo_.dragging(); }

 private:
  ScreenMapping mapping(const EditorState& state, const ViewRect& rect) const;
  double sceneRadius(const EditorState& state) const;
  bool placeGizmo(const EditorState& state);
  void pick(EditorState& state, const ViewRect& rect, glm::dvec2 mouse, bool extend);

  // Framing waits for the viewport's shape, known in handleInput and draw.
  void framePending(const ViewRect& rect);

  Gizmo gizmo_;
  std::optional<Bounds> pendingFrame_;
  int hot_ = -1;
  bool navigating_ = false;
  bool clickPending_ = false;
};

}  // namespace strata::ui
