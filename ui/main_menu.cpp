// The menu bar, its keyboard shortcuts, and what happens once a file has been chosen.
#include <imgui.h>
#include <imgui_internal.h>  // ClosePopupsOverWindow, GetTopMostPopupModal (Escape on menus)
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <filesystem>

#include "engine/document/commands.h"
#include "engine/io/mesh_formats.h"
#include "ui/editor_actions.h"
#include "ui/panels.h"

namespace strata::ui {
namespace {

// New and Open replace the document: ask first when it has unsaved changes.
void replaceOrAsk(EditorState& state, PendingReplace action) {
  if (state.document.dirty())
    state.pendingReplace = action;
  else
    performReplace(state, action);
}

}  // namespace

void requestQuit(EditorState& state) {
  if (state.exportJob && state.exportJob->status().running)
    state.askingQuitDuringExport = true;  // then quitOrAskAboutChanges (panel_modals.cpp)
  else
    quitOrAskAboutChanges(state);
}

void quitOrAskAboutChanges(EditorState& state) {
  replaceOrAsk(state, {PendingReplace::Quit, ""});
}

void performReplace(EditorState& state, const PendingReplace& action) {
  if (action.kind == PendingReplace::New) newDocument(state);
  if (action.kind == PendingReplace::Quit) state.quitNow = true;
  if (action.kind == PendingReplace::Open) {
    if (action.path.empty())
      state.dialog.open(DialogPurpose::Open, dialogFolder(state));
    else
      openDocument(state, action.path);
  }
}

bool saveOrAsk(EditorState& state, std::optional<PendingReplace> then) {
  if (saveDocument(state)) return true;
  if (!state.overwriteQuestion.empty()) state.afterOverwrite = then;  // asked: panel_modals.cpp
  if (state.document.path().empty()) {
    state.afterSaveAs = then;
    state.dialog.open(DialogPurpose::SaveAs, saveAsSuggestion(state));
  }
  return false;
}

void drawMainMenu(EditorState& state) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("New", "Ctrl+N")) replaceOrAsk(state, {PendingReplace::New, ""});
    if (ImGui::MenuItem("Open...", "Ctrl+O")) replaceOrAsk(state, {PendingReplace::Open, ""});
    if (ImGui::BeginMenu("Open recent", !state.recentFiles.empty())) {
      for (const auto& f : state.recentFiles)
        if (ImGui::MenuItem(f.c_str())) replaceOrAsk(state, {PendingReplace::Open, f});
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Save", "Ctrl+S")) saveOrAsk(state, std::nullopt);
    if (ImGui::MenuItem("Save as...", "Ctrl+Shift+S"))
      state.dialog.open(DialogPurpose::SaveAs, saveAsSuggestion(state));
    ImGui::Separator();
    if (ImGui::MenuItem("Import mesh...")) {
      state.importPlacement.reset();
      state.dialog.open(DialogPurpose::ImportMesh, importFolder(state));
    }
    if (ImGui::MenuItem("Export...", "Ctrl+E"))
      state.dialog.open(DialogPurpose::Export, exportSuggestion(state));
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) requestQuit(state);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Edit")) {
    std::string undoText = "Undo " + state.document.undoLabel();
    std::string redoText = "Redo " + state.document.redoLabel();
    if (ImGui::MenuItem(undoText.c_str(), "Ctrl+Z", false, state.document.canUndo())) undo(state);
    if (ImGui::MenuItem(redoText.c_str(), "Ctrl+Y", false, state.document.canRedo())) redo(state);
    ImGui::Separator();
    const bool any = !state.selection.empty();
    if (ImGui::MenuItem("Cut", "Ctrl+X", false, any)) cutSelection(state);
    if (ImGui::MenuItem("Copy", "Ctrl+C", false, any)) copySelection(state);
    if (ImGui::MenuItem("Paste", "Ctrl+V", false, !state.clipboard.empty())) pasteClipboard(state);
    if (ImGui::BeginMenu("New parts")) {
      for (PlaceMode mode : {PlaceMode::Add, PlaceMode::Cut, PlaceMode::Intersect})
        if (ImGui::MenuItem(placeModeName(mode), nullptr, state.placeMode == mode))
          state.placeMode = mode;
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Duplicate", "Ctrl+D", false, any)) duplicateSelection(state);
    if (ImGui::MenuItem("Instance", "Alt+D", false, any)) instanceSelection(state);
    if (ImGui::MenuItem("Delete", "Del", false, any)) deleteSelection(state);
    if (ImGui::MenuItem("Hide / show", "H", false, any)) toggleSelectionHidden(state);
    if (ImGui::MenuItem("Rename", "F2", false, any)) state.renaming = primarySelection(state);
    if (ImGui::BeginMenu("Group as", any)) {
      for (NodeKind k : operationKinds())
        if (ImGui::MenuItem(kindLabel(k), k == groupKindKeepingRoles(state) ? "Ctrl+G" : nullptr))
          groupSelection(state, k);
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Select none", "Esc", false, any)) clearSelection(state);
    ImGui::Separator();
    const bool several = state.selection.size() > 1;
    const bool aligning = ImGui::BeginMenu("Align to the active part", several);
    // Said only while its entries are not shown (the tip would cover them).
    if (!aligning && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip(
          "Moves the other selected parts so that their bounds line up with the "
          "active (last clicked) part's");
    if (aligning) {
      const char* edges[3] = {"min", "centre", "max"};
      for (int axis = 0; axis < 3; ++axis)
        for (int e = 0; e < 3; ++e) {
          const std::string label = std::string("xyz").substr(size_t(axis), 1) + " " + edges[e];
          if (ImGui::MenuItem(label.c_str())) alignSelection(state, axis, AlignEdge(e));
        }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Drop to ground", nullptr, false, any)) dropSelectionToGround(state);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Moves the selected parts to rest on z = 0");
    if (ImGui::MenuItem("Clear measurements", nullptr, false,
                        !state.document.scene().measurements.empty()))
      clearMeasurements(state);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("View all", "Home")) state.requestViewAll = true;
    if (ImGui::MenuItem("Frame selected", "F")) state.requestFrameSelected = true;
    // AxisView order: front, back, right, left, top, bottom (camera.h).
    const char* views[6] = {"Front", "Back", "Right", "Left", "Top", "Bottom"};
    const char* keys[6] = {"1", "Ctrl+1", "3", "Ctrl+3", "7", "Ctrl+7"};
    if (ImGui::BeginMenu("Look from")) {
      for (int v = 0; v < 6; ++v)
        if (ImGui::MenuItem(views[v], keys[v])) state.requestAxisView = v;
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Orthographic / perspective", "5")) state.requestToggleOrtho = true;
    ImGui::Separator();
    if (ImGui::MenuItem("Move", "W", state.gizmoMode == GizmoMode::Move))
      state.gizmoMode = GizmoMode::Move;
    if (ImGui::MenuItem("Rotate", "E", state.gizmoMode == GizmoMode::Rotate))
      state.gizmoMode = GizmoMode::Rotate;
    if (ImGui::MenuItem("Scale", "R", state.gizmoMode == GizmoMode::Scale))
      state.gizmoMode = GizmoMode::Scale;
    ImGui::MenuItem("Snap", nullptr, &state.snap.enabled);
    if (ImGui::MenuItem("Measure", "M", state.measure.active))
      setMeasuring(state, !state.measure.active);
    ImGui::Separator();
    ImGui::MenuItem("Ghosts of all cutters", "G", &state.showAllGhosts);
    ImGui::MenuItem("Ground grid", nullptr, &state.showGrid);
    ImGui::MenuItem("Diagnostics", nullptr, &state.showDiagnostics);
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Shortcuts", "F1")) state.showShortcuts = true;
    ImGui::EndMenu();
  }
  // At the right end, after the menus where the window is narrow.
  const std::string label = documentLabel(state);
  const float right = ImGui::GetWindowWidth() - ImGui::CalcTextSize(label.c_str()).x - 16.0f;
  ImGui::SameLine(std::max(ImGui::GetCursorPosX(), right));
  ImGui::TextDisabled("%s", label.c_str());
  ImGui::EndMainMenuBar();
}

void handleShortcuts(EditorState& state) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || state.dialog.isOpen() || state.pendingReplace) return;
  // A menu or context menu is open (not a modal dialog, which takes its own keys): Escape closes
  // it and no shortcut reaches the scene behind it.
  if (ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel)) {
    if (!ImGui::GetTopMostPopupModal() && keyPressed(state, GLFW_KEY_ESCAPE))
      ImGui::ClosePopupsOverWindow(nullptr, false);
    return;
  }
  const int ctrl = GLFW_MOD_CONTROL, shift = GLFW_MOD_SHIFT;
  if (keyPressed(state, GLFW_KEY_S, ctrl)) saveOrAsk(state, std::nullopt);
  if (keyPressed(state, GLFW_KEY_S, ctrl | shift))
    state.dialog.open(DialogPurpose::SaveAs, saveAsSuggestion(state));
  if (keyPressed(state, GLFW_KEY_N, ctrl)) replaceOrAsk(state, {PendingReplace::New, ""});
  if (keyPressed(state, GLFW_KEY_O, ctrl)) replaceOrAsk(state, {PendingReplace::Open, ""});
  if (keyPressed(state, GLFW_KEY_E, ctrl))
    state.dialog.open(DialogPurpose::Export, exportSuggestion(state));
  if (keyPressed(state, GLFW_KEY_Q, ctrl)) requestQuit(state);
  if (io.WantCaptureKeyboard) {
    // A field dragged with the mouse holds the keyboard: Ctrl+Z, redo and Escape call its drag
    // off, as they do a gizmo's (Ctrl+Z was ignored there, and the drag committed on release).
    if (state.fieldDragHeld) {
      if (keyPressed(state, GLFW_KEY_Z, ctrl))
        undo(state);
      else if (keyPressed(state, GLFW_KEY_Z, ctrl | shift) || keyPressed(state, GLFW_KEY_Y, ctrl))
        redo(state);
      else if (keyPressed(state, GLFW_KEY_ESCAPE))
        state.cancelFieldDrag = true;
    }
    return;
  }
  if (keyPressed(state, GLFW_KEY_Z, ctrl)) undo(state);
  if (keyPressed(state, GLFW_KEY_Z, ctrl | shift) || keyPressed(state, GLFW_KEY_Y, ctrl))
    redo(state);
  if (keyPressed(state, GLFW_KEY_D, ctrl)) duplicateSelection(state);
  if (keyPressed(state, GLFW_KEY_C, ctrl)) copySelection(state);
  if (keyPressed(state, GLFW_KEY_X, ctrl)) cutSelection(state);
  if (keyPressed(state, GLFW_KEY_V, ctrl)) pasteClipboard(state);
  if (keyPressed(state, GLFW_KEY_D, GLFW_MOD_ALT)) instanceSelection(state);
  if (keyPressed(state, GLFW_KEY_G, ctrl)) groupSelection(state, groupKindKeepingRoles(state));
  if (keyPressed(state, GLFW_KEY_DELETE) || keyPressed(state, GLFW_KEY_BACKSPACE))
    deleteSelection(state);
  if (keyPressed(state, GLFW_KEY_H)) toggleSelectionHidden(state);
  if (keyPressed(state, GLFW_KEY_F1)) state.showShortcuts = !state.showShortcuts;
  if (keyPressed(state, GLFW_KEY_G)) state.showAllGhosts = !state.showAllGhosts;
  if (keyPressed(state, GLFW_KEY_F2) && !state.selection.empty())
    state.renaming = primarySelection(state);
  if (keyPressed(state, GLFW_KEY_M)) setMeasuring(state, !state.measure.active);
  if (keyPressed(state, GLFW_KEY_ESCAPE)) {
    // The innermost thing under way first: a drag, the sheet, the measure tool, the selection.
    if (state.gizmoDragging)
      state.cancelGizmoDrag = true;
    else if (state.showShortcuts)
      state.showShortcuts = false;
    else if (state.measure.active)
      measureEscape(state);
    else
      clearSelection(state);
  }
}

namespace {
// Opens the import dialog (panel_modals.cpp) for the mesh at `path`, with the last unit and up
// axis chosen; `placement`: where a palette drag dropped it (none: placed by the import).
void askImportOptions(EditorState& state, const std::string& path,
                      const std::optional<Placement>& placement) {
  PendingImport import;
  import.path = path;
  import.unit = state.lastImportUnit;
  import.upAxis = state.lastImportUpAxis;
  import.placement = placement;
  state.pendingImport = import;
}
}  // namespace

void handleDialogResult(EditorState& state) {
  std::string path;
  if (!state.dialog.takeResult(&path)) {
    if (!state.dialog.isOpen()) state.afterSaveAs.reset();  // cancelled, or none asked
    return;
  }
  switch (state.dialog.purpose()) {
    case DialogPurpose::Open:
      if (meshFormatFor(path, MeshAccess::Read)) {
        // A mesh chosen to open (an artist met a JSON parser's error on an STL): imported into
        // this scene, through the import dialog, which says so and can be cancelled.
        logInfo(state, path + " is a mesh, not a scene: importing it into this scene");
        askImportOptions(state, path, std::nullopt);
        break;
      }
      openDocument(state, path);
      break;
    case DialogPurpose::SaveAs: {
      const std::string suffix = ".json";
      if (path.size() < suffix.size() ||
          path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0)
        path += ".strata.json";
      std::optional<PendingReplace> then = state.afterSaveAs;
      state.afterSaveAs.reset();
      if (saveDocumentAs(state, path) && then) performReplace(state, *then);
      break;
    }
    case DialogPurpose::Export:
      state.pendingExportPath = path;  // the export dialog asks for its options
      state.exportEstimate.reset();
      break;
    case DialogPurpose::ImportMesh: {
      state.lastImportFolder = std::filesystem::path(path).parent_path().string();
      askImportOptions(state, path, state.importPlacement);
      state.importPlacement.reset();
      break;
    }
  }
}

}  // namespace strata::ui
