#include "ui/pattern_guides.h"

#include "ui/measure_tool.h"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <algorithm>

#include "engine/document/commands.h"
#include "engine/document/measurement.h"
#include "engine/kinds/patterns.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

// The pattern `id` names or, for a part, the nearest mirror or circular array above it; 0 none.
NodeId guidedPattern(const NodePtr& root, NodeId id) {
  std::vector<const Node*> path;
  if (!pathToNode(root, id, &path)) return 0;
  for (size_t k = path.size(); k-- > 0;) {
    const Pattern p = patternOf(path[k]->kind);
    if (p == Pattern::Mirror || p == Pattern::Circular) return path[k]->id;
  }
  return 0;
}

}  // namespace

std::vector<PatternGuide> patternGuides(const EditorState& state) {
  std::vector<PatternGuide> guides;
  const NodePtr& root = state.document.root();
  if (!root) return guides;
  std::vector<NodeId> patterns;
  for (NodeId id : state.selection) {
    const NodeId p = guidedPattern(root, id);
    if (p && std::find(patterns.begin(), patterns.end(), p) == patterns.end())
      patterns.push_back(p);
  }
  for (NodeId id : patterns) {
    const NodePtr node = findNode(root, id);
    if (!node) continue;
    double reach = selectionBounds(root, {id}).longestSide();
    if (!(reach > 0.0)) reach = sceneBounds(root).longestSide();
    if (!(reach > 0.0)) continue;
    reach *= 0.6;
    const glm::dmat4 world = nodeWorldMatrix(root, id);
    const int a = std::clamp(node->pattern.axis, 0, 2);
    const auto direction = [&](int k) {
      const glm::dvec3 d(world[k]);
      const double length = glm::length(d);
      return length > 0.0 ? d / length : glm::dvec3(0.0);
    };
    PatternGuide g;
    g.node = id;
    g.point = glm::dvec3(world * glm::dvec4(node->pattern.center, 1.0));
    const std::string name = quotedName(*node);
    if (patternOf(node->kind) == Pattern::Mirror) {
      g.plane = true;
      g.u = direction((a + 1) % 3) * reach;
      g.v = direction((a + 2) % 3) * reach;
      g.label = "mirror plane of " + name + " (across " + axisName(a) + ")";
    } else {
      g.u = direction(a) * reach;
      g.label = "axis of " + name + " (" + axisName(a) + ")";
    }
    guides.push_back(g);
  }
  return guides;
}

void drawPatternGuides(const std::vector<PatternGuide>& guides, const ScreenMapping& view,
                       double x0, double y0, std::vector<ScreenBox>* taken) {
  if (guides.empty()) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(float(x0), float(y0)),
                     ImVec2(float(x0 + view.size.x), float(y0 + view.size.y)), true);
  const ImU32 line = IM_COL32(90, 205, 255, 220), fill = IM_COL32(90, 205, 255, 36);
  auto screen = [&](const glm::dvec3& p, ImVec2* out) {
    glm::dvec2 px;
    if (!view.toScreen(p, &px)) return false;
    *out = ImVec2(float(x0 + px.x), float(y0 + px.y));
    return true;
  };
  for (const PatternGuide& g : guides) {
    ImVec2 at;
    if (g.plane) {
      ImVec2 c[4];
      bool shown = true;
      const glm::dvec3 corners[4] = {g.point - g.u - g.v, g.point + g.u - g.v, g.point + g.u + g.v,
                                     g.point - g.u + g.v};
      for (int k = 0; k < 4; ++k) shown = shown && screen(corners[k], &c[k]);
      if (!shown) continue;
      draw->AddQuadFilled(c[0], c[1], c[2], c[3], fill);
      draw->AddQuad(c[0], c[1], c[2], c[3], line, 1.5f);
      at = c[3];
    } else {
      // Dashed: twelve dashes along the axis.
      constexpr int kDashes = 12;
      for (int k = 0; k < kDashes; ++k) {
        ImVec2 p, q;
        const double s = -1.0 + 2.0 * k / kDashes, t = s + 1.2 / kDashes;
        if (screen(g.point + g.u * s, &p) && screen(g.point + g.u * t, &q))
          draw->AddLine(p, q, line, 2.0f);
      }
      if (!screen(g.point + g.u, &at)) continue;
    }
    // Off the gizmo and the names drawn before it (view pixels), within the view.
    const ImVec2 size = ImGui::CalcTextSize(g.label.c_str());
    const glm::dvec2 wantedLo(at.x - x0 + 4.0, at.y - y0 - size.y);
    const ScreenBox box =
        placedLabelBox({wantedLo - 1.0, wantedLo + glm::dvec2(size.x, size.y) + 1.0}, *taken,
                       {0.0, kViewTextTop + ImGui::GetTextLineHeightWithSpacing()}, view.size,
                       ImGui::GetTextLineHeight() * 0.5);
    taken->push_back(box);
    // A dark outline under the text: readable over light parts as over the background.
    const ImVec2 text(float(x0 + box.lo.x + 1.0), float(y0 + box.lo.y + 1.0));
    for (const ImVec2 d : {ImVec2(1, 1), ImVec2(-1, 1), ImVec2(1, -1), ImVec2(-1, -1)})
      draw->AddText(ImVec2(text.x + d.x, text.y + d.y), IM_COL32(20, 22, 26, 220), g.label.c_str());
    draw->AddText(text, line, g.label.c_str());
  }
  draw->PopClipRect();
}

}  // namespace strata::ui
