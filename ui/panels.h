// The editor's ImGui panels. Each draws from and acts on EditorState; edits go through
// editor_actions.h (one undo step each; ImGui widgets that are held down, such as drags, make one
// step from activation to deactivation). The UI thread, between ImGui::NewFrame and Render.
#pragma once

#include "ui/editor_state.h"

namespace strata::ui {

// Drag and drop from the palette: the payload is an int, a NodeKind or kImportMeshItem.
constexpr const char* kPalettePayload = "STRATA_PALETTE";
constexpr int kImportMeshItem = -1;

// Pixels. The four panel sizes as shown: what the artist set (`wanted`: the splitters, the layout
// file) kept within the window by clampLayout, so that a window made small and then large again
// shows the panels as they were set.
struct PanelSizes {
  float leftWidth = 320.0f;
  float rightWidth = 330.0f;
  float paletteHeight = 330.0f;  // the palette, under the outliner: all its rows at 1000 px
  float previewHeight = 310.0f;  // the preview settings, under the inspector
};
struct PanelLayout : PanelSizes {
  float menuHeight = 0.0f;
  float statusHeight = 0.0f;
  float paletteRows = 0.0f;  // the palette's rows beyond paletteHeight (paletteRowsHeight)
  PanelSizes wanted;
};

// The resolutions the Preview panel's slider lands on when dragged, and its - and + buttons step
// through: the powers of two and the halves between them (16, 24, 32, 48, ... 768, 1024).
// resolutionStepNearest is the one nearest `resolution` on a log scale (ties: the coarser);
// resolutionStepAfter the next one finer (`direction` +1) or coarser (-1) than `resolution`,
// which need not be one (a typed 300 steps to 384 or 256), kept within [lo, hi].
int resolutionStepNearest(int resolution);
int resolutionStepAfter(int resolution, int direction, int lo, int hi);

// The modifier keys held now, as dropMode's bits (editor_actions.h; ImGui's keyboard state).
int heldDropModifiers();

// Menu bar (File, Edit, View) and the keyboard shortcuts of its items.
void drawMainMenu(EditorState& state);
void handleShortcuts(EditorState& state);
// Reacts to a chosen file (open, save as, export, import).
void handleDialogResult(EditorState& state);
// Quit (the menu, Ctrl+Q, the window's close button): asks first when an export is running
// (quitting cancels it) and when the document has unsaved changes.
void requestQuit(EditorState& state);
// Quit now, or ask about unsaved changes first (whatever an export is doing).
void quitOrAskAboutChanges(EditorState& state);
// Does what a PendingReplace asks (new, open, quit, recover), without asking.
void performReplace(EditorState& state, const PendingReplace& action);
// Saves; an untitled document opens Save As instead, and `then` runs after that save succeeds.
// Returns whether the document was saved now.
bool saveOrAsk(EditorState& state, std::optional<PendingReplace> then);

// The items of a part's menu (rename, hide, duplicate, group, role, ...), inside an open popup:
// the outliner's row menu and the view's right-click menu.
void contextMenuItems(EditorState& state, const NodePtr& node);

// Left column: the scene tree and the palette of things to add.
void drawOutliner(EditorState& state, const PanelLayout& layout);
void drawPalette(EditorState& state, const PanelLayout& layout);
// The palette's height as drawn: layout.paletteHeight (what its splitter sets) plus
// layout.paletteRows, set each frame from paletteRowsHeight: its mode row, its hint line and a
// row of buttons for every three primitives beyond six (needs the ImGui context).
float paletteHeightFor(const PanelLayout& layout);
float paletteRowsHeight();
// Right column: the selected node's properties and the preview settings.
void drawInspector(EditorState& state, const PanelLayout& layout);
void drawPreviewPanel(EditorState& state, const PanelLayout& layout);
// Bottom: backend, grid, surfels, evaluation times, frame time.
void drawStatusBar(EditorState& state, const PanelLayout& layout);
// Floating: stages, nodes, memory, messages.
void drawDiagnostics(EditorState& state);
// Modal questions (recovery, unsaved changes) and the export progress window.
void drawModals(EditorState& state);
// The shortcut sheet (F1): every key and mouse gesture of the editor, while showShortcuts.
void drawShortcutSheet(EditorState& state);

}  // namespace strata::ui
