#include "ui/measure_tool.h"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "engine/geometry/mesh_world_bounds.h"
#include "engine/kinds/primitives.h"
#include "ui/editor_actions.h"
#include "ui/editor_state.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

const glm::vec4 kMeasureColor(1.0f, 0.86f, 0.25f, 1.0f);

// The part's box in its own frame (a primitive's or a mesh's bounds); empty for other nodes.
Bounds localBox(const Node& node) {
  Bounds b;
  if (isPrimitive(node.kind)) return primitiveLocalBounds(node.kind, node.params);
  if (node.kind == NodeKind::Mesh) return meshWorldBounds(node.mesh, glm::dmat4(1.0));
  return b;
}

struct SnapPoint {
  glm::dvec3 world;
  const char* what;  // "corner" or "edge midpoint"
};

// The corners and edge midpoints of `box` placed by `m`.
std::vector<SnapPoint> snapPoints(const Bounds& box, const glm::dmat4& m) {
  std::vector<SnapPoint> out;
  if (box.empty()) return out;
  const glm::dvec3 lo = box.min, hi = box.max, mid = 0.5 * (lo + hi);
  for (int i = 0; i < 27; ++i) {
    const int c[3] = {i % 3, (i / 3) % 3, i / 9};  // 0 min, 1 middle, 2 max per axis
    int middles = 0;
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a) {
      p[a] = c[a] == 0 ? lo[a] : c[a] == 2 ? hi[a] : mid[a];
      middles += c[a] == 1 ? 1 : 0;
    }
    if (middles <= 1)  // 8 corners, 12 edge midpoints
      out.push_back({glm::dvec3(m * glm::dvec4(p, 1.0)), middles ? "edge midpoint" : "corner"});
  }
  return out;
}

bool openValid(const EditorState& state) {
  const MeasureTool& t = state.measure;
  return t.open >= 0 && t.openRevision == state.document.revision() &&
         size_t(t.open) < state.document.scene().measurements.size() &&
         state.document.scene().measurements[size_t(t.open)].points.size() == 2;
}

void addMarker(const ScreenMapping& view, const glm::dvec3& p, std::vector<LineVertex>* out) {
  // About 5 pixels each way whatever the depth.
  const double depth = view.ortho ? 1.0 : std::max(glm::dot(p - view.eye, view.forward), 1e-9);
  const double r = 5.0 * view.unitsPerPixel * depth;
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 d(0.0);
    d[a] = r;
    out->push_back(lineVertex(p - d, kMeasureColor));
    out->push_back(lineVertex(p + d, kMeasureColor));
  }
}

// The boxes of the labels drawn so far this frame, and what they keep clear of: a new label that
// would cover one moves off it (measurements whose middles fall together stay readable).
struct LabelBoxes {
  std::vector<ScreenBox> taken;
};

// The on-screen segment (pixels) a label names, when it has one.
struct LabelledSegment {
  ImVec2 a, b;
};

// A label centred on `at` (screen pixels), or placed by labelCentre when it names `segment`:
// moved into the view and off the labels already drawn and the gizmo (placedLabelBox); not drawn
// where none of it would have been in the view.
void label(ImDrawList* draw, ImVec2 at, const std::string& text, LabelBoxes* boxes, ImVec2 viewLo,
           ImVec2 viewHi, const std::optional<LabelledSegment>& segment = std::nullopt) {
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  if (segment) {
    const glm::dvec2 centre =
        measureLabelCentre({segment->a.x, segment->a.y}, {segment->b.x, segment->b.y},
                           {size.x * 0.5 + 4.0, size.y * 0.5 + 2.0});
    at = ImVec2(float(centre.x), float(centre.y));
  }
  const ScreenBox wanted{{at.x - size.x * 0.5 - 4.0, at.y - size.y * 0.5 - 2.0},
                         {at.x + size.x * 0.5 + 4.0, at.y + size.y * 0.5 + 2.0}};
  if (wanted.hi.x <= viewLo.x || wanted.lo.x >= viewHi.x || wanted.hi.y <= viewLo.y ||
      wanted.lo.y >= viewHi.y)
    return;
  const ScreenBox box = placedLabelBox(wanted, boxes->taken, {viewLo.x, viewLo.y},
                                       {viewHi.x, viewHi.y}, ImGui::GetTextLineHeight() * 0.5);
  boxes->taken.push_back(box);
  const ImVec2 lo(float(box.lo.x), float(box.lo.y)), hi(float(box.hi.x), float(box.hi.y));
  draw->AddRectFilled(lo, hi, IM_COL32(20, 22, 26, 210), 3.0f);
  draw->AddRect(lo, hi, IM_COL32(255, 220, 64, 160), 3.0f);
  draw->AddText(ImVec2(lo.x + 4.0f, lo.y + 2.0f), IM_COL32(255, 236, 150, 255), text.c_str());
}

}  // namespace

ScreenBox placedLabelBox(ScreenBox box, const std::vector<ScreenBox>& taken, glm::dvec2 viewLo,
                         glm::dvec2 viewHi, double step) {
  const auto intoView = [&](ScreenBox b) {
    const glm::dvec2 shift =
        glm::max(viewLo - b.lo, glm::dvec2(0.0)) - glm::max(b.hi - viewHi, glm::dvec2(0.0));
    b.lo += shift;
    b.hi += shift;
    return b;
  };
  const auto clear = [&](const ScreenBox& b) {
    for (const ScreenBox& t : taken)
      if (b.overlaps(t)) return false;
    return true;
  };
  box = intoView(box);
  if (clear(box)) return box;
  for (int k = 1; k <= 32; ++k)
    for (const double direction : {1.0, -1.0}) {
      ScreenBox moved = box;
      moved.lo.y += direction * k * step;
      moved.hi.y += direction * k * step;
      // Only where it still lies whole in the view (one pushed back in would cover again).
      if (moved.lo.y < viewLo.y || moved.hi.y > viewHi.y) continue;
      if (clear(moved)) return moved;
    }
  return box;
}

glm::dvec2 measureLabelCentre(glm::dvec2 a, glm::dvec2 b, glm::dvec2 half) {
  const glm::dvec2 mid = 0.5 * (a + b);
  const double marker = 6.0;  // addMarker's 5 pixels, and one
  auto covers = [&](glm::dvec2 p) {
    return std::abs(p.x - mid.x) < half.x + marker && std::abs(p.y - mid.y) < half.y + marker;
  };
  if (!covers(a) && !covers(b)) return mid;
  const glm::dvec2 d = b - a;
  const double length = glm::length(d);
  glm::dvec2 normal(0.0, -1.0);  // a segment seen end-on: above its point
  if (length > 0.5) normal = glm::dvec2(d.y, -d.x) / length;
  if (normal.y > 0.0) normal = -normal;
  const double away = std::abs(normal.x) * half.x + std::abs(normal.y) * half.y + marker;
  return mid + normal * away;
}

glm::dvec3 snapMeasurePoint(const EditorState& state, const ScreenMapping& view, const PickHit& hit,
                            glm::dvec2 mouse, const std::function<bool(const glm::dvec3&)>& shown,
                            std::string* what, const std::optional<glm::dvec3>& capEdge) {
  if (hit.cap && capEdge) {
    if (what) *what = "the section cap's edge, as drawn (to about a cell)";
    return *capEdge;
  }
  if (what) *what = hit.cap ? "section cap" : "surface";
  const NodePtr& root = state.document.root();
  NodePtr leaf = findNode(root, hit.leaf);
  if (!leaf) return hit.position;
  // Of the points within reach on screen, the nearest to the surface point clicked: a corner
  // behind the part, on the same line of sight, is not taken for the one in front.
  double best = std::numeric_limits<double>::infinity();
  glm::dvec3 snapped = hit.position;
  for (const SnapPoint& s : snapPoints(localBox(*leaf), nodeWorldMatrix(root, leaf->id))) {
    glm::dvec2 pixel;
    if (!view.toScreen(s.world, &pixel) || glm::length(pixel - mouse) > kMeasureSnapPixels)
      continue;
    const double d = glm::length(s.world - hit.position);
    if (d >= best || (shown && !shown(s.world))) continue;
    best = d;
    snapped = s.world;
    if (what) *what = s.what;
  }
  return snapped;
}

void measureClick(EditorState& state, uint32_t leaf, const glm::dvec3& world) {
  MeasureTool& tool = state.measure;
  const NodePtr& root = state.document.root();
  const MeasurePoint point = attachPoint(root, leaf, world);
  std::vector<Measurement> list = state.document.scene().measurements;
  if (openValid(state)) {
    list[size_t(tool.open)].points.push_back(point);
    tool.open = -1;
    guarded(state, [&] { state.document.applyMeasurements("measure an angle", list); });
    return;
  }
  tool.open = -1;
  if (!tool.first) {
    tool.first = point;
    tool.firstWorld = world;
    return;
  }
  // The first point's part may have gone since it was placed: then it stays where it was.
  MeasurePoint first = *tool.first;
  if (first.node != 0 && !findNode(root, first.node)) first = attachPoint(root, 0, tool.firstWorld);
  list.push_back(Measurement{{first, point}});
  tool.first.reset();
  if (guarded(state, [&] { state.document.applyMeasurements("measure", list); })) {
    tool.open = int(list.size()) - 1;
    tool.openRevision = state.document.revision();
  }
}

void measureEscape(EditorState& state) {
  MeasureTool& tool = state.measure;
  if (tool.first || openValid(state)) {
    tool.first.reset();
    tool.open = -1;
    return;
  }
  setMeasuring(state, false);
}

void setMeasuring(EditorState& state, bool on) {
  state.measure.active = on;
  state.measure.first.reset();
  state.measure.open = -1;
}

void removeMeasurement(EditorState& state, size_t index) {
  std::vector<Measurement> list = state.document.scene().measurements;
  if (index >= list.size()) return;
  list.erase(list.begin() + long(index));
  state.measure.open = -1;
  guarded(state, [&] { state.document.applyMeasurements("remove a measurement", list); });
}

void clearMeasurements(EditorState& state) {
  state.measure.open = -1;
  state.measure.first.reset();
  guarded(state, [&] { state.document.applyMeasurements("clear measurements", {}); });
}

std::string distanceText(const EditorState& state, double distance) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.4g %s", distance,
                unitSymbol(state.document.scene().settings.unit));
  return text;
}

std::string measureSummary(const EditorState& state, const MeasureValues& v) {
  std::string s = distanceText(state, v.distance) + "  (dx " + distanceText(state, v.delta.x) +
                  ", dy " + distanceText(state, v.delta.y) + ", dz " +
                  distanceText(state, v.delta.z) + ")";
  if (v.hasAngle) {
    char angle[48];
    std::snprintf(angle, sizeof(angle), "%.2f deg", v.angleDegrees);
    s += "; then " + distanceText(state, v.distance2) + ", angle " + angle;
  }
  return s;
}

void appendMeasureLines(const EditorState& state, const ScreenMapping& view,
                        std::vector<LineVertex>* overlay) {
  const NodePtr& root = state.document.root();
  for (const Measurement& m : state.document.scene().measurements) {
    const MeasureValues v = measureValues(root, m);
    overlay->push_back(lineVertex(v.a, kMeasureColor));
    overlay->push_back(lineVertex(v.b, kMeasureColor));
    addMarker(view, v.a, overlay);
    addMarker(view, v.b, overlay);
    if (m.points.size() == 3) {
      overlay->push_back(lineVertex(v.b, kMeasureColor));
      overlay->push_back(lineVertex(v.c, kMeasureColor));
      addMarker(view, v.c, overlay);
    }
  }
  if (state.measure.active && state.measure.first) {
    const MeasurePoint& first = *state.measure.first;
    const bool gone = first.node != 0 && !findNode(root, first.node);
    addMarker(view, gone ? state.measure.firstWorld : pointInWorld(root, first), overlay);
  }
}

std::vector<ScreenBox> drawMeasureLabels(const EditorState& state, const ScreenMapping& view,
                                         double x0, double y0,
                                         const std::vector<ScreenBox>& keepClear) {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  // Within the view: a label beyond its edge showed through the translucent panels beside it.
  draw->PushClipRect(ImVec2(float(x0), float(y0)),
                     ImVec2(float(x0 + view.size.x), float(y0 + view.size.y)), true);
  const NodePtr& root = state.document.root();
  // Below the view's two lines of text at its top (its name and the tool's hint).
  const ImVec2 viewLo{float(x0), float(y0 + kViewTextTop + ImGui::GetTextLineHeightWithSpacing())};
  const ImVec2 viewHi{float(x0 + view.size.x), float(y0 + view.size.y)};
  auto screen = [&](const glm::dvec3& p, ImVec2* out) {
    glm::dvec2 px;
    if (!view.toScreen(p, &px)) return false;
    *out = ImVec2(float(x0 + px.x), float(y0 + px.y));
    return true;
  };
  // The segment from p to q on screen, where both ends are in front of the camera.
  auto segment = [&](const glm::dvec3& p, const glm::dvec3& q) -> std::optional<LabelledSegment> {
    LabelledSegment s;
    if (!screen(p, &s.a) || !screen(q, &s.b)) return std::nullopt;
    return s;
  };
  LabelBoxes boxes;
  for (const ScreenBox& b : keepClear)  // in window pixels, as the labels
    boxes.taken.push_back({b.lo + glm::dvec2(x0, y0), b.hi + glm::dvec2(x0, y0)});
  for (const Measurement& m : state.document.scene().measurements) {
    const MeasureValues v = measureValues(root, m);
    ImVec2 at;
    if (screen(0.5 * (v.a + v.b), &at))
      label(draw, at,
            distanceText(state, v.distance) + "\ndx " + distanceText(state, v.delta.x) + "  dy " +
                distanceText(state, v.delta.y) + "  dz " + distanceText(state, v.delta.z),
            &boxes, viewLo, viewHi, segment(v.a, v.b));
    if (m.points.size() == 3) {
      if (screen(0.5 * (v.b + v.c), &at))
        label(draw, at, distanceText(state, v.distance2), &boxes, viewLo, viewHi,
              segment(v.b, v.c));
      char angle[48];
      std::snprintf(angle, sizeof(angle), "%.2f\u00B0", v.angleDegrees);
      if (v.hasAngle && screen(v.b, &at))
        label(draw, ImVec2(at.x, at.y - 22.0f), angle, &boxes, viewLo, viewHi);
    }
  }
  draw->PopClipRect();
  std::vector<ScreenBox> taken;
  for (const ScreenBox& b : boxes.taken)
    taken.push_back({b.lo - glm::dvec2(x0, y0), b.hi - glm::dvec2(x0, y0)});
  return taken;
}

}  // namespace strata::ui
