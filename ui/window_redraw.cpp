#include "ui/window_redraw.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace strata::ui {

namespace {

bool sameCommand(const DrawListRecord::Command& a, const DrawListRecord::Command& b) {
  return a.clip.x == b.clip.x && a.clip.y == b.clip.y && a.clip.z == b.clip.z &&
         a.clip.w == b.clip.w && a.texture == b.texture && a.vertexOffset == b.vertexOffset &&
         a.indexOffset == b.indexOffset && a.elements == b.elements && a.callback == b.callback &&
         a.callbackData == b.callbackData;
}

template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

PixelRect unite(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// The parts of `r` outside `cut` (at most four), appended to *out.
void subtract(const PixelRect& r, const PixelRect& cut, std::vector<PixelRect>* out) {
  if (!r.overlaps(cut)) {
    if (!r.empty()) out->push_back(r);
    return;
  }
  if (r.y0 < cut.y0) out->push_back({r.x0, r.y0, r.x1, cut.y0});  // below
  if (cut.y1 < r.y1) out->push_back({r.x0, cut.y1, r.x1, r.y1});  // above
  const int y0 = std::max(r.y0, cut.y0), y1 = std::min(r.y1, cut.y1);
  if (r.x0 < cut.x0) out->push_back({r.x0, y0, cut.x0, y1});  // left
  if (cut.x1 < r.x1) out->push_back({cut.x1, y0, r.x1, y1});  // right
}

}  // namespace

bool DrawListRecord::sameDrawing(const DrawListRecord& o) const {
  if (owner != o.owner || !(rect == o.rect) || commands.size() != o.commands.size()) return false;
  for (size_t i = 0; i < commands.size(); ++i)
    if (!sameCommand(commands[i], o.commands[i])) return false;
  return sameBytes(indices, o.indices) && sameBytes(vertices, o.vertices);
}

DrawListRecord recordDrawList(const ImDrawList& list, const ImDrawData& data, int width,
                              int height) {
  DrawListRecord r;
  r.owner = list._OwnerName ? list._OwnerName : "";
  r.vertices.assign(list.VtxBuffer.Data, list.VtxBuffer.Data + list.VtxBuffer.Size);
  r.indices.assign(list.IdxBuffer.Data, list.IdxBuffer.Data + list.IdxBuffer.Size);
  // The vertices' bounds in framebuffer pixels: a pixel drawn has its centre in a triangle,
  // so within floor(lowest) .. ceil(highest) on each axis.
  float lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f};
  for (const ImDrawVert& v : r.vertices) {
    lo[0] = std::min(lo[0], v.pos.x), hi[0] = std::max(hi[0], v.pos.x);
    lo[1] = std::min(lo[1], v.pos.y), hi[1] = std::max(hi[1], v.pos.y);
  }
  PixelRect reach;
  if (!r.vertices.empty()) {
    const ImVec2 origin = data.DisplayPos, scale = data.FramebufferScale;
    reach.x0 = int(std::floor((lo[0] - origin.x) * scale.x));
    reach.x1 = int(std::ceil((hi[0] - origin.x) * scale.x));
    reach.y0 = height - int(std::ceil((hi[1] - origin.y) * scale.y));
    reach.y1 = height - int(std::floor((lo[1] - origin.y) * scale.y));
  }
  bool callback = false;
  for (const ImDrawCmd& c : list.CmdBuffer) {
    r.commands.push_back({c.ClipRect, c.TextureId, c.VtxOffset, c.IdxOffset, c.ElemCount,
                          c.UserCallback, c.UserCallbackData});
    // A user callback may draw anything: the whole framebuffer (resetting the render state
    // draws nothing).
    if (c.UserCallback && c.UserCallback != ImDrawCallback_ResetRenderState) callback = true;
    if (c.ElemCount > 0) r.rect = unite(r.rect, scissorBox(c, data, height).intersect(reach));
  }
  if (callback) r.rect = {0, 0, width, height};
  r.rect = r.rect.intersect({0, 0, width, height});
  if (r.rect.empty()) r.rect = {};
  return r;
}

std::vector<PixelRect> disjointRects(const std::vector<PixelRect>& rects) {
  std::vector<PixelRect> out;
  for (const PixelRect& r : rects) {
    std::vector<PixelRect> pieces{r}, next;
    for (const PixelRect& kept : out) {
      next.clear();
      for (const PixelRect& p : pieces) subtract(p, kept, &next);
      pieces.swap(next);
    }
    for (const PixelRect& p : pieces)
      if (!p.empty()) out.push_back(p);
  }
  return out;
}

std::vector<PixelRect> damagedRects(const std::vector<DrawListRecord>& previous,
                                    const std::vector<DrawListRecord>& current,
                                    const PixelRect& always) {
  std::vector<PixelRect> damage{always};
  for (size_t i = 0; i < std::max(previous.size(), current.size()); ++i) {
    if (i < previous.size() && i < current.size() && previous[i].sameDrawing(current[i])) continue;
    if (i < current.size()) damage.push_back(current[i].rect);
    if (i < previous.size()) damage.push_back(previous[i].rect);
  }
  return disjointRects(damage);
}

void WindowRedraw::begin(const ImDrawData& data, int width, int height, const PixelRect& view,
                         bool viewUnchanged) {
  const PixelRect window{0, 0, width, height};
  if (width != width_ || height != height_) all_ = true;  // a new back buffer
  width_ = width;
  height_ = height;
  std::vector<DrawListRecord> current;
  if (keeps_) {
    current.reserve(size_t(std::max(0, data.CmdListsCount)));
    for (int i = 0; i < data.CmdListsCount; ++i)
      current.push_back(recordDrawList(*data.CmdLists[i], data, width, height));
  }
  whole_ = all_ || !keeps_;
  viewKept_ = !whole_ && viewUnchanged;
  viewRepaints_.clear();
  if (whole_) {
    rects_ = disjointRects({view.intersect(window), window});
  } else if (viewKept_) {
    // The panels' damage alone; where it reaches the view, the view is drawn again there.
    rects_ = damagedRects(records_, current, PixelRect{});
    for (const PixelRect& r : rects_)
      if (r.overlaps(view)) viewRepaints_.push_back(r.intersect(view));
  } else {
    rects_ = damagedRects(records_, current, view.intersect(window));
  }
  all_ = false;
  records_ = std::move(current);

  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
  glClearColor(kWindowBackground[0], kWindowBackground[1], kWindowBackground[2],
               kWindowBackground[3]);
  glEnable(GL_SCISSOR_TEST);
  for (const PixelRect& r : rects_) {
    if (!viewKept_ && view.intersect(window) == r) continue;  // the view covers it
    glScissor(r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);
}

void WindowRedraw::drawPanels(PanelRenderer& renderer, const ImDrawData& data) const {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (whole_)
    renderer.draw(data, width_, height_, {0, 0, width_, height_});
  else
    for (const PixelRect& r : rects_) renderer.draw(data, width_, height_, r);
}

long long WindowRedraw::pixelsRedrawn() const {
  long long n = 0;
  for (const PixelRect& r : rects_) n += r.area();
  return n;
}

}  // namespace strata::ui
