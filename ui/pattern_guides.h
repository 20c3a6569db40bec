// Where a mirror's plane and a circular array's axis lie, drawn over the view while the pattern
// (or a part inside it) is selected: an artist could not tell across what a mirror reflected or
// about what an array turned, the gizmo sitting at the pattern's origin away from its parts.
//
// Threads: the UI thread.
#pragma once

#include <glm/vec3.hpp>

#include <string>
#include <vector>

#include "engine/document/node.h"
#include "ui/editor_state.h"
#include "ui/gizmo.h"

namespace strata::ui {

// One guide in world coordinates (scene units). A plane: the rectangle point +- u +- v. An axis:
// the segment point +- u (v is zero).
struct PatternGuide {
  NodeId node = 0;
  bool plane = false;
  glm::dvec3 point{0.0};
  glm::dvec3 u{0.0}, v{0.0};
  std::string label;  // "mirror plane of \"ribs\" (across x)"
};

// The guides of the selected mirrors and circular arrays and of the nearest such pattern above
// each selected part, each once; a guide reaches 0.6 of the pattern's largest world extent from
// its point (or of the scene's where the pattern has none).
std::vector<PatternGuide> patternGuides(const EditorState& state);

// Draws `guides` (patternGuides) over the view, whose top-left corner is at window pixel (x0, y0).
// Each name is placed off the boxes in `*taken` (view pixels: the gizmo's; an axis's name covered
// the gizmo's arrow head: an artist's test), and its own box is added to them.
void drawPatternGuides(const std::vector<PatternGuide>& guides, const ScreenMapping& view,
                       double x0, double y0, std::vector<ScreenBox>* taken);

}  // namespace strata::ui
