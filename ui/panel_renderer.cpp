#include "ui/panel_renderer.h"

#include <algorithm>
#include <cstddef>

namespace strata::ui {

PixelRect scissorBox(const ImDrawCmd& command, const ImDrawData& data, int height) {
  const ImVec2 origin = data.DisplayPos, scale = data.FramebufferScale;
  const float minX = (command.ClipRect.x - origin.x) * scale.x;
  const float minY = (command.ClipRect.y - origin.y) * scale.y;
  const float maxX = (command.ClipRect.z - origin.x) * scale.x;
  const float maxY = (command.ClipRect.w - origin.y) * scale.y;
  if (maxX <= minX || maxY <= minY) return {};
  PixelRect box;
  box.x0 = int(minX);
  box.y0 = int(float(height) - maxY);
  box.x1 = box.x0 + int(maxX - minX);
  box.y1 = box.y0 + int(maxY - minY);
  return box;
}

PanelRenderer::PanelRenderer() : program_("panel.vert", "panel.frag") {
  ImGuiIO& io = ImGui::GetIO();
  io.BackendRendererName = "strata_panel_renderer";
  io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;  // glDrawElementsBaseVertex

  unsigned char* pixels = nullptr;
  int width = 0, height = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
  glGenTextures(1, &atlas_);
  glBindTexture(GL_TEXTURE_2D, atlas_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
  glBindTexture(GL_TEXTURE_2D, 0);
  io.Fonts->SetTexID(ImTextureID(intptr_t(atlas_)));

  glGenVertexArrays(1, &vertexArray_);
  glGenBuffers(1, &vertices_);
  glGenBuffers(1, &indices_);
  glBindVertexArray(vertexArray_);
  glBindBuffer(GL_ARRAY_BUFFER, vertices_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_);
  const auto stride = GLsizei(sizeof(ImDrawVert));
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, pos)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, uv)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride,
                        reinterpret_cast<void*>(offsetof(ImDrawVert, col)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

PanelRenderer::~PanelRenderer() {
  ImGuiIO& io = ImGui::GetIO();
  if (io.Fonts->TexID == ImTextureID(intptr_t(atlas_))) io.Fonts->SetTexID(ImTextureID(0));
  io.BackendRendererName = nullptr;
  glDeleteTextures(1, &atlas_);
  glDeleteBuffers(1, &vertices_);
  glDeleteBuffers(1, &indices_);
  glDeleteVertexArrays(1, &vertexArray_);
}

void PanelRenderer::setUp(const ImDrawData& data, int width, int height) {
  // As Dear ImGui's backend: alpha blending (colour over, alpha accumulated), no culling, depth
  // or stencil, the scissor on, polygons filled.
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glEnable(GL_SCISSOR_TEST);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glViewport(0, 0, width, height);
  const float l = data.DisplayPos.x, r = data.DisplayPos.x + data.DisplaySize.x;
  const float t = data.DisplayPos.y, b = data.DisplayPos.y + data.DisplaySize.y;
  const glm::mat4 projection(2.0f / (r - l), 0.0f, 0.0f, 0.0f,  //
                             0.0f, 2.0f / (t - b), 0.0f, 0.0f,  //
                             0.0f, 0.0f, -1.0f, 0.0f,           //
                             (r + l) / (l - r), (t + b) / (b - t), 0.0f, 1.0f);
  program_.use();
  program_.set("projection", projection);
  program_.set("atlas", 0);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vertexArray_);
  glBindBuffer(GL_ARRAY_BUFFER, vertices_);
}

void PanelRenderer::draw(const ImDrawData& data, int width, int height, const PixelRect& within) {
  if (width <= 0 || height <= 0 || within.empty()) return;
  setUp(data, width, height);
  const GLenum indexType = sizeof(ImDrawIdx) == 2 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
  for (int n = 0; n < data.CmdListsCount; ++n) {
    const ImDrawList& list = *data.CmdLists[n];
    // Nothing uploaded for a list that draws nothing within the rectangle.
    bool touches = false;
    for (const ImDrawCmd& c : list.CmdBuffer)
      touches = touches || c.UserCallback != nullptr ||
                (c.ElemCount > 0 && !scissorBox(c, data, height).intersect(within).empty());
    if (!touches) continue;
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(list.VtxBuffer.Size) * GLsizeiptr(sizeof(ImDrawVert)),
                 list.VtxBuffer.Data, GL_STREAM_DRAW);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 GLsizeiptr(list.IdxBuffer.Size) * GLsizeiptr(sizeof(ImDrawIdx)),
                 list.IdxBuffer.Data, GL_STREAM_DRAW);
    for (const ImDrawCmd& c : list.CmdBuffer) {
      if (c.UserCallback) {
        if (c.UserCallback == ImDrawCallback_ResetRenderState)
          setUp(data, width, height);
        else {
          glScissor(within.x0, within.y0, within.x1 - within.x0, within.y1 - within.y0);
          c.UserCallback(&list, &c);  // must draw within the scissor box it is given
        }
        continue;
      }
      const PixelRect box = scissorBox(c, data, height).intersect(within);
      if (c.ElemCount == 0 || box.empty()) continue;
      glScissor(box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0);
      glBindTexture(GL_TEXTURE_2D, GLuint(intptr_t(c.GetTexID())));
      glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(c.ElemCount), indexType,
                               reinterpret_cast<void*>(size_t(c.IdxOffset) * sizeof(ImDrawIdx)),
                               GLint(c.VtxOffset));
    }
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace strata::ui
