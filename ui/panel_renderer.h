// Dear ImGui's draw data in OpenGL: the panels, menus and text of the editor. Does what Dear
// ImGui's OpenGL 3 backend does (the same shader, blending and scissor boxes, so the same
// pixels), and can draw only within a rectangle of the framebuffer: each command's scissor box
// is cut to it, which is what redrawing only part of the window needs (window_redraw.h) and
// the backend cannot do (it sets the scissor itself).
//
// Threads: the UI thread, with the GL context current. Construct after the fonts are added
// (theme.h): it uploads the font atlas and names it as the atlas's texture.
#pragma once

#include <imgui.h>

#include "ui/gl_program.h"
#include "ui/pixel_rect.h"

namespace strata::ui {

// The scissor box of `command` in a framebuffer `height` pixels high, as Dear ImGui's OpenGL
// backend sets it (the clip rectangle scaled, its corner and size truncated); empty when the
// command is clipped away.
PixelRect scissorBox(const ImDrawCmd& command, const ImDrawData& data, int height);

class PanelRenderer {
 public:
  PanelRenderer();
  ~PanelRenderer();
  PanelRenderer(const PanelRenderer&) = delete;
  PanelRenderer& operator=(const PanelRenderer&) = delete;

  // Draws every list of `data` into the bound framebuffer of width x height pixels, only within
  // `within`. Leaves blending and the scissor test off, the blend function ImGui's, the viewport
  // the whole framebuffer, texture unit 0 active with no texture, no program, no vertex array.
  void draw(const ImDrawData& data, int width, int height, const PixelRect& within);

 private:
  void setUp(const ImDrawData& data, int width, int height);

  GlProgram program_;
  GLuint vertexArray_ = 0, vertices_ = 0, indices_ = 0, atlas_ = 0;
};

}  // namespace strata::ui
