// Splitters between the editor's panels, and the layout they set remembered between runs.
//
// Four handles: the left column's and the right column's inner edges (drag sideways), the top
// of the palette and of the preview panel (drag up and down). The layout file holds the four
// sizes as "name value" lines ($XDG_CONFIG_HOME/strata/layout.txt beside the recent files).
//
// Threads: the UI thread, between ImGui::NewFrame and Render (drawSplitters).
#pragma once

#include <string>

#include "ui/panels.h"

namespace strata::ui {

// Draws the handles over the panels' edges and applies a drag to `layout` (sizes kept within
// what leaves every panel and the view usable in the window). Returns true when a drag ended
// this frame (time to save).
bool drawSplitters(PanelLayout& layout);
// The sizes shown: layout.wanted kept within the window's `width` x `height` (pixels), the
// columns giving up width in proportion in a narrow window.
void clampLayout(PanelLayout& layout, float width, float height);

// The sizes saved in `path` (wanted and shown) over the defaults of `layout`; a missing or
// damaged file (or a line it does not know) leaves the defaults.
PanelLayout readPanelLayout(const std::string& path, PanelLayout layout);
// Writes the four wanted sizes atomically, creating the folder. Throws strata::Error.
void writePanelLayout(const std::string& path, const PanelLayout& layout);

}  // namespace strata::ui
