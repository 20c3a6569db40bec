// The editor's look: ImGui colours and spacing, the font (DejaVu Sans when installed, with the
// glyphs the outliner uses; ImGui's built-in font otherwise), and the glyph of each node kind.
#pragma once

#include <vector>

#include "engine/document/node.h"

namespace strata::ui {

// Call once after ImGui::CreateContext(), before the first frame. `scale`: content scale of the
// monitor (1 on ordinary screens).
void applyTheme(float scale);
// A short symbol for the kind: "∪" "∩" "−" for operations and shapes for leaves (ASCII when the
// font lacks them).
const char* kindGlyph(NodeKind kind);
// Where rows of operation buttons start: at each new family (Booleans, modifiers, patterns) and
// after `perRow` buttons of one family. One entry per kind of `ops`.
std::vector<bool> operationRowStarts(const std::vector<NodeKind>& ops, int perRow);
// Symbols for visible / hidden.
const char* visibleGlyph(bool visible);

}  // namespace strata::ui
