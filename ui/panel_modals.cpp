// Questions that block the document (recover the last session? discard unsaved changes?) and
// the export progress window.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "engine/eval/evaluator.h"
#include "engine/export/job_estimate.h"
#include "engine/io/mesh_formats.h"
#include "engine/io/mesh_io.h"
#include "engine/io/user_files.h"
#include "engine/util/error.h"
#include "engine/util/limits.h"
#include "ui/editor_actions.h"
#include "ui/import_options.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"
#include "ui/text_fit.h"
#include "ui/typed_value.h"

namespace strata::ui {
namespace {

void centreNext() {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.4f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
}

void recoveryQuestion(EditorState& state) {
  const char* title = "Recover unsaved work?";
  if (state.offerRecovery && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  centreNext();
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (state.recoveryOffers.empty()) {  // answered elsewhere
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  // Which document, and from when: read when the offer changes.
  static std::string described;
  static RecoveryInfo info;
  const RecoveryOffer& offer = state.recoveryOffers.front();
  if (described != offer.path) info = describeRecoveryFile(described = offer.path);
  const std::string what = info.origin.empty() ? "an untitled document" : info.origin;
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36.0f);
  ImGui::TextWrapped("An editor ended without saving its changes to %s.", what.c_str());
  if (!info.writtenAt.empty()) ImGui::TextWrapped("Last autosaved %s.", info.writtenAt.c_str());
  if (state.recoveryOffers.size() > 1)
    ImGui::TextWrapped(
        "%zu more such %s: asked about after this one is discarded or left for later; "
        "after a Recover, at the next start.",
        state.recoveryOffers.size() - 1,
        state.recoveryOffers.size() == 2 ? "document" : "documents");
  ImGui::TextDisabled("%s", offer.path.c_str());
  ImGui::PopTextWrapPos();
  if (ImGui::Button("Recover", ImVec2(120, 0))) recoverDocument(state);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Open it in place of the document shown (undo starts from there)");
  ImGui::SameLine();
  if (ImGui::Button("Later", ImVec2(120, 0))) postponeRecovery(state);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Leave it for the next start");
  ImGui::SameLine();
  if (ImGui::Button("Discard", ImVec2(120, 0))) discardRecovery(state);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Put it aside (the last %d discarded are kept in %s/discarded)",
                      kKeptDiscards, state.recoveryDir.c_str());
  if (!state.offerRecovery) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

// A save over a file that changed on disk since it was opened or saved here.
void overwriteQuestion(EditorState& state) {
  const char* title = "File changed on disk";
  if (!state.overwriteQuestion.empty() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  centreNext();
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36.0f);
  ImGui::TextWrapped("%s.", state.overwriteQuestion.c_str());
  ImGui::TextWrapped("Saving replaces what it holds now (kept once, as %s.bak).",
                     state.document.path().c_str());
  ImGui::PopTextWrapPos();
  bool close = false;
  if (ImGui::Button("Overwrite", ImVec2(120, 0))) {
    const std::optional<PendingReplace> then = state.afterOverwrite;
    if (saveDocumentAs(state, state.document.path()) && then) performReplace(state, *then);
    close = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Save as...", ImVec2(120, 0))) {
    state.afterSaveAs = state.afterOverwrite;
    state.dialog.open(DialogPurpose::SaveAs, state.document.path());
    close = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0)) || keyPressed(state, GLFW_KEY_ESCAPE)) close = true;
  if (close) {
    state.overwriteQuestion.clear();
    state.afterOverwrite.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

void unsavedQuestion(EditorState& state) {
  const char* title = "Unsaved changes";
  if (state.pendingReplace && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  centreNext();
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::Text("%s has unsaved changes.", state.document.name().c_str());
  bool proceed = false, close = false;
  if (ImGui::Button("Save", ImVec2(110, 0))) {
    // An untitled document asks where first; the action follows the save (main_menu.cpp).
    proceed = saveOrAsk(state, state.pendingReplace);
    close = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Discard", ImVec2(110, 0))) proceed = true;
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(110, 0)) || keyPressed(state, GLFW_KEY_ESCAPE)) close = true;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keep working on it (Esc)");
  if (proceed && state.pendingReplace) {
    const PendingReplace action = *state.pendingReplace;  // performReplace may open another
    performReplace(state, action);
    close = true;
  }
  if (close) {
    state.pendingReplace.reset();
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
}

// Quitting while an export runs would end it unfinished (an artist's Ctrl+Q closed the editor
// at "evaluate 10%" without a word): asked first; cancelling the export then quits as usual
// (asking about unsaved changes next).
void quitDuringExportQuestion(EditorState& state) {
  const char* title = "Export running";
  if (state.askingQuitDuringExport && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  if (!state.askingQuitDuringExport) return;
  centreNext();
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  const bool running = state.exportJob && state.exportJob->status().running;
  if (running) {
    const ExportStatus s = state.exportJob->status();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
    // In its check the file is already in place (export_scene.h): only the check is cut short.
    if (s.stage == "check")
      ImGui::TextWrapped(
          "An export to %s is being checked (%.0f%%): the file is written. Quitting stops the "
          "check; the file stays, unchecked.",
          s.path.c_str(), s.fraction * 100.0);
    else
      ImGui::TextWrapped(
          "An export to %s is running (%s %.0f%%). Quitting cancels it: the file is "
          "not written.",
          s.path.c_str(), s.stage.c_str(), s.fraction * 100.0);
    ImGui::PopTextWrapPos();
  }
  // It ended meanwhile: the question closes and the export window shows how it ended (a failure
  // is read, not quit past); Ctrl+Q again quits.
  bool close = !running;
  bool quit = false;
  if (ImGui::Button("Keep exporting", ImVec2(160, 0)) || keyPressed(state, GLFW_KEY_ESCAPE))
    close = true, quit = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Go on working while it exports (Esc)");
  ImGui::SameLine();
  // Not cancelled here: quitting ends it (the editor's end cancels and joins the job), and
  // backing out of the unsaved-changes question that may follow leaves it running.
  if (ImGui::Button("Cancel export and quit", ImVec2(200, 0))) close = quit = true;
  if (close) {
    state.askingQuitDuringExport = false;
    ImGui::CloseCurrentPopup();
  }
  ImGui::EndPopup();
  if (quit) quitOrAskAboutChanges(state);
}

// The menu of a part right-clicked in the view (Viewport: the part selected first).
void viewContextMenu(EditorState& state) {
  const char* id = "##view context menu";
  static NodeId shown = 0;
  if (state.viewContextMenu) {
    shown = state.viewContextMenu;
    state.viewContextMenu = 0;
    ImGui::OpenPopup(id);
  }
  if (!ImGui::BeginPopup(id)) return;
  const NodePtr node = findNode(state.document.root(), shown);
  if (node)
    contextMenuItems(state, node);
  else
    ImGui::CloseCurrentPopup();  // the part went meanwhile (an undo)
  ImGui::EndPopup();
}

// An export refused before it started: its file, why, and another file to choose.
void exportNotStartedWindow(EditorState& state) {
  if (!state.exportNotStarted) return;
  bool open = true;
  centreNext();
  ImGui::SetNextWindowSize(ImVec2(460, 0), ImGuiCond_Appearing);
  ImGui::Begin("Export", &open, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::TextWrapped("%s", state.exportNotStarted->path.c_str());
  ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.45f, 1.0f), "not started: nothing was written");
  ImGui::TextWrapped("%s", state.exportNotStarted->why.c_str());
  if (ImGui::Button("Choose another file...", ImVec2(200, 0))) {
    state.exportNotStarted.reset();
    state.dialog.open(DialogPurpose::Export, exportSuggestion(state));
    ImGui::End();
    return;
  }
  ImGui::SameLine();
  if (ImGui::Button("Close", ImVec2(120, 0))) open = false;
  ImGui::End();
  if (!open) state.exportNotStarted.reset();
}

void exportWindow(EditorState& state) {
  exportNotStartedWindow(state);
  if (!state.exportJob) return;
  logExportEnd(state);
  ExportStatus s = state.exportJob->status();
  bool open = true;
  // Its top edge in one place from one export to the next (centred, it moved with the height of
  // its first frame, and Cancel with it: an artist clicked the bar instead, twice).
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.25f),
                          ImGuiCond_Appearing, ImVec2(0.5f, 0.0f));
  // One width from its first frame to its last, its lines wrapped in it: sized by its content,
  // its first frame of a report was narrow, cut at "1 compo" (an artist's test).
  const float width = ImGui::GetFontSize() * 40.0f;
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
  ImGui::Begin("Export", s.running ? nullptr : &open, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::TextWrapped("%s", s.path.c_str());
  if (s.simplifyCells > 0.0)
    ImGui::TextDisabled("resolution %d, simplified within %.2f cells", s.resolution,
                        s.simplifyCells);
  else
    ImGui::TextDisabled("resolution %d", s.resolution);
  if (s.running) {
    // The bar and Cancel right under the lines every export has, the estimate (of varying
    // length) below them: Cancel stays where it was from one export to the next, and Close
    // takes its place once the export has ended.
    char overlay[96];
    std::snprintf(overlay, sizeof(overlay), "%s %.0f%%", s.stage.c_str(), s.fraction * 100.0);
    ImGui::ProgressBar(float(s.fraction), ImVec2(-1, 0), overlay);
    if (ImGui::Button("Cancel", ImVec2(120, 0))) state.exportJob->cancel();
  } else if (ImGui::Button("Close", ImVec2(120, 0)) ||
             (keyPressed(state, GLFW_KEY_ESCAPE) && !ImGui::IsAnyItemActive())) {
    // Where Cancel was, above the report (of varying length): at its foot it moved from one
    // export to the next, and a click meant for it selected a part behind (an artist's test).
    // Esc closes the ended export's window, as it closes the dialogs.
    open = false;
  }
  if (!s.estimate.empty())  // wrapped at spaces: ImGui's wrapping parted "1.3 GiB" at its point
    for (const std::string& line :
         wrapAtSpaces("estimate: " + s.estimate, ImGui::GetContentRegionAvail().x,
                      [](const std::string& t) { return ImGui::CalcTextSize(t.c_str()).x; }))
      ImGui::TextUnformatted(line.c_str());
  if (s.running) {
    // (The bar and Cancel above.)
  } else if (s.succeeded) {
    const MeshCheck& c = s.check;
    const bool passed = s.checkPassed();
    ImGui::TextColored(passed ? ImVec4(0.5f, 0.9f, 0.5f, 1.0f) : ImVec4(1.0f, 0.5f, 0.4f, 1.0f),
                       passed           ? "written and checked: watertight"
                       : c.watertight() ? "written, but the check FAILED"
                                        : "written, but NOT watertight");
    if (!s.fileDifference.empty()) ImGui::TextWrapped("%s", s.fileDifference.c_str());
    ImGui::TextWrapped("%zu triangles, %zu vertices, %d component(s), genus %d", c.triangles,
                       c.vertices, c.components, c.genus);
    // Several bodies: what joins them said plainly (a sphere resting on a box was two bodies in
    // the file, "watertight", and nothing said why: an artist's test).
    if (passed && c.components > 1) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      ImGui::TextWrapped(
          "%d separate bodies: parts that only touch (at a point or along an edge) are not "
          "joined; overlap them to make one body",
          c.components);
      ImGui::PopStyleColor();
    }
    // Parts the export's cells could not keep (the report said nothing of a sphere lost in
    // it: an artist's test).
    // A few in full, the rest counted (the log holds them all): a window of every warning grew
    // past the screen and its Close button out of reach (an artist's test).
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    const size_t shownWarnings = s.warnings.size() > 4 ? 3 : s.warnings.size();
    for (size_t i = 0; i < shownWarnings; ++i) ImGui::TextWrapped("%s", s.warnings[i].c_str());
    if (s.warnings.size() > shownWarnings)
      ImGui::TextWrapped("and %zu more warnings (all of them in the log: View > Diagnostics)",
                         s.warnings.size() - shownWarnings);
    ImGui::PopStyleColor();
    const SimplifyReport& r = s.simplify;
    const char* unit = unitSymbol(state.document.scene().settings.unit);
    if (r.refused)
      ImGui::TextWrapped("not simplified: %s", r.refusedWhy);
    else if (r.trianglesBefore > 0)
      ImGui::TextWrapped(
          "simplified from %zu triangles (%.1f%%); deviation from the unsimplified surface "
          "at most %.3g %s (%.2f cells, measured)",
          r.trianglesBefore, 100.0 * double(r.trianglesAfter) / double(r.trianglesBefore),
          r.measured.bound(), unit,
          s.simplifyCells * r.measured.bound() / std::max(r.tolerance, 1e-300));
    ImGui::TextWrapped("boundary edges %zu, non-manifold %zu, misoriented %zu", c.boundaryEdges,
                       c.nonManifoldEdges, c.misorientedEdges);
    ImGui::TextWrapped("volume %.6g %s^3, area %.6g %s^2, %.2f s", c.volume, unit, c.area, unit,
                       s.seconds);
  } else if (s.cancelledAfterWrite) {
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "cancelled after the file was written");
    ImGui::TextWrapped("%s", exportCancelledAfterWriteText);
  } else if (s.cancelled) {
    ImGui::TextWrapped("%s", exportCancelledText(s).c_str());
  } else {
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.45f, 1.0f), s.refused ? "not started" : "failed");
    ImGui::TextWrapped("%s", s.error.c_str());
    if (s.refused && ImGui::Button("Export anyway", ImVec2(160, 0))) {
      const std::string path = s.path;
      const int resolution = s.resolution;
      const double simplifyCells = s.simplifyCells;
      state.exportJob.reset();
      startExport(state, path, resolution, simplifyCells, /*insist=*/true);
      ImGui::End();
      return;
    }
  }
  if (!s.notice.empty()) ImGui::TextWrapped("%s", s.notice.c_str());
  ImGui::End();
  if (!open) state.exportJob.reset();
}

std::string countText(uint64_t n) {
  char text[32];
  if (n >= 10000000)
    std::snprintf(text, sizeof(text), "%.0f million", double(n) / 1e6);
  else if (n >= 1000000)
    std::snprintf(text, sizeof(text), "%.1f million", double(n) / 1e6);
  else if (n >= 10000)
    std::snprintf(text, sizeof(text), "%.0f,000", std::floor(double(n) / 1000.0));
  else
    std::snprintf(text, sizeof(text), "%llu", static_cast<unsigned long long>(n));
  return text;
}

// Cancels the dialog's estimate and keeps it until it has stopped; drops the stopped ones.
void retireEstimate(EditorState& state) {
  if (state.exportEstimate) {
    state.exportEstimate->cancel();
    state.retiredEstimates.push_back(std::move(state.exportEstimate));
  }
  auto& retired = state.retiredEstimates;
  retired.erase(
      std::remove_if(retired.begin(), retired.end(),
                     [](const std::unique_ptr<ExportEstimateJob>& job) { return job->done(); }),
      retired.end());
}

// The export dialog: the export's own resolution and simplification, with the triangles they
// will make (estimated on a background thread, export_estimate_job.h), then export or cancel.
void exportOptionsDialog(EditorState& state) {
  const char* title = "Export: options###export options";
  if (state.pendingExportPath && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  centreNext();
  // One width whatever is shown (the simplify row, a note): the preset buttons stay where they
  // were from one opening to the next (an artist's click landed on 2048 where 1024 had been).
  const float width = ImGui::GetFontSize() * 40.0f;
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (!state.pendingExportPath) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  const Scene& scene = state.document.scene();
  int& resolution = state.exportResolution;
  if (resolution <= 0) resolution = scene.settings.resolution;
  ImGui::TextUnformatted(state.pendingExportPath->c_str());
  ImGui::SetNextItemWidth(160);
  // Out of range: set to the nearest end and said, once the number is entered (not while it is
  // typed: "5" on the way to "512"), until another value is.
  static std::string clampNote;
  static std::optional<int> outOfRange;
  if (ImGui::IsWindowAppearing()) {
    clampNote.clear();
    outOfRange.reset();
  }
  const int before = resolution;
  numberFieldNext("cells along the longest side");
  ImGui::InputInt("cells along the longest side", &resolution, 64, 256);
  const bool typing = ImGui::IsItemActive();
  if (resolution != before) {
    clampNote.clear();
    outOfRange.reset();
  }
  if (resolution < kMinResolution || resolution > kMaxResolution) {
    outOfRange = resolution;
    resolution = std::clamp(resolution, kMinResolution, kMaxResolution);
  }
  // A number set to the nearest end this frame is shown before anything is exported with it:
  // the Enter that entered it does not export.
  static int clampedAtFrame = -1000;
  if (outOfRange && !typing) clampedAtFrame = ImGui::GetFrameCount();
  // Half a second or so: the click that left the field does not export what it was set to.
  const bool justClamped = ImGui::GetFrameCount() - clampedAtFrame < 30;
  if (outOfRange && !typing) {
    clampNote = std::to_string(*outOfRange) + " cells: an export takes " +
                std::to_string(kMinResolution) + " to " + std::to_string(kMaxResolution) +
                "; set to " + std::to_string(resolution);
    outOfRange.reset();
  }
  if (!clampNote.empty())
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", clampNote.c_str());
  for (int preset : {256, 512, 1024, 2048}) {
    char label[16];
    std::snprintf(label, sizeof(label), "%d", preset);
    // The preset the resolution stands at (typed, remembered from the last export, or clicked)
    // looks pressed: a remembered 1024 showed four alike buttons (an artist's test).
    const bool current = resolution == preset;
    if (current)
      ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    if (ImGui::Button(label, ImVec2(56, 0))) {
      resolution = preset;
      clampNote.clear();
    }
    if (current) ImGui::PopStyleColor();
    ImGui::SameLine();
  }
  ImGui::NewLine();
  // A scene no grid can hold (too large or too small to measure: Evaluator::gridFor) is said
  // here and not exported, instead of its error ending the editor. Parts too small or thin for
  // the export's cells are said before it runs (the preview's panel said it at the preview's
  // resolution, the export nothing: an artist's test). Both worked out from the parts' bounds
  // when the resolution or the document changes, not every frame.
  const auto key = std::make_pair(state.document.revision(), resolution);
  if (state.exportGridFor != key) {
    state.exportGridFor = key;
    state.exportGrid = Grid();
    state.exportNoGrid.clear();
    state.exportSmallParts.clear();
    try {
      state.exportGrid = Evaluator::gridFor(scene, resolution);
      state.exportSmallParts = Evaluator::smallPartWarnings(scene, resolution);
    } catch (const Error& e) {
      state.exportNoGrid = e.what();
    }
  }
  const Grid& grid = state.exportGrid;
  const std::string& noGrid = state.exportNoGrid;
  if (noGrid.empty())
    ImGui::TextDisabled("cell %.4g %s; the preview is at %d cells", grid.h,
                        scene.settings.unit.c_str(), scene.settings.resolution);
  else
    ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.45f, 1.0f), "%s", noGrid.c_str());
  if (noGrid.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    const size_t shown = std::min<size_t>(state.exportSmallParts.size(), 3);
    for (size_t i = 0; i < shown; ++i) ImGui::TextWrapped("%s", state.exportSmallParts[i].c_str());
    if (state.exportSmallParts.size() > shown)
      ImGui::TextWrapped("and %zu more (parts too small or thin for these cells, or missing)",
                         state.exportSmallParts.size() - shown);
    ImGui::PopStyleColor();
  }
  ImGui::Checkbox("simplify", &state.exportSimplify);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Fewer triangles: edges collapsed where the surface stays within the\n"
        "tolerance; topology, orientation, sharp edges and seams between\n"
        "parts kept. Flat faces become a few large triangles.");
  if (state.exportSimplify) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(160);
    ImGui::SliderFloat("within cells", &state.exportSimplifyCells, 0.05f, 2.0f, "%.2f");
    state.exportSimplifyCells = std::clamp(state.exportSimplifyCells, 0.05f, 2.0f);
    ImGui::SameLine();
    ImGui::TextDisabled("= %.3g %s", double(state.exportSimplifyCells) * grid.h,
                        scene.settings.unit.c_str());
  }
  // The triangles, estimated off the UI thread for this choice; one for an older choice is
  // cancelled and retired (never joined here).
  const double cells = state.exportSimplify ? double(state.exportSimplifyCells) : 0.0;
  ExportEstimateJob* estimate = state.exportEstimate.get();
  const bool current =
      estimate && estimate->resolution() == resolution && estimate->simplifyCells() == cells;
  // Not while a field or slider is held and changing; once its value has stood for half a second
  // it is estimated (a typed 5000 stayed "estimating the triangles..." for as long as its field
  // kept the focus, and Tab did not leave it: an artist's test).
  static std::pair<int, double> seen{-1, -1.0};
  static double seenSince = 0.0;
  if (seen != std::make_pair(resolution, cells)) {
    seen = {resolution, cells};
    seenSince = ImGui::GetTime();
  }
  const bool settled = !ImGui::IsAnyItemActive() || ImGui::GetTime() - seenSince > 0.5;
  if (!current && settled) {
    retireEstimate(state);
    state.exportEstimate = std::make_unique<ExportEstimateJob>(
        state.document.snapshot(), *state.pendingExportPath, resolution, cells, state.makeBackend);
  }
  estimate = state.exportEstimate.get();
  // Two lines, always (the counts, then the time and memory): Export and Cancel below must not
  // move when the answer comes (a click aimed at one would land elsewhere).
  const float estimateTop = ImGui::GetCursorPosY();
  if (estimate && estimate->done() && current) {
    const TriangleEstimate e = estimate->result();
    // The file's size with the triangles, before Export (it was told only once it ran).
    const MeshFormat* format = meshFormatFor(*state.pendingExportPath, MeshAccess::Write);
    const uint64_t written = cells > 0.0 ? e.simplified : e.triangles;
    const std::string file =
        format ? ", a " + bytesText(double(written) * format->bytesPerTriangle) + " file" : "";
    if (!estimate->error().empty())
      ImGui::TextDisabled("no estimate: %s", estimate->error().c_str());
    else if (cells > 0.0)
      ImGui::Text("about %s triangles, simplified from about %s%s", countText(e.simplified).c_str(),
                  countText(e.triangles).c_str(), file.c_str());
    else
      ImGui::Text("about %s triangles%s", countText(e.triangles).c_str(), file.c_str());
    // Time and memory before Export (they were told only once it ran: an artist's test); a job
    // too small to probe takes a second or so.
    const JobEstimate job = estimate->jobEstimate();
    if (estimate->error().empty() && job.probed)
      ImGui::Text("about %s of memory, %s", bytesText(double(job.peakBytes)).c_str(),
                  durationText(job.seconds).c_str());
  } else {
    ImGui::TextDisabled("estimating the triangles, the time and the memory...");
  }
  const float twoLines = 2.0f * ImGui::GetTextLineHeightWithSpacing();
  if (ImGui::GetCursorPosY() < estimateTop + twoLines) ImGui::SetCursorPosY(estimateTop + twoLines);
  ImGui::Separator();
  // Not on the frame a typed value was set to the range's end (its note shows first), nor for a
  // scene no grid holds.
  ImGui::BeginDisabled(justClamped || !noGrid.empty());
  const bool exportNow = ImGui::Button("Export", ImVec2(120, 0)) ||
                         (keyPressed(state, GLFW_KEY_ENTER) && !justClamped && noGrid.empty());
  ImGui::EndDisabled();
  if (exportNow) {
    const std::string path = *state.pendingExportPath;
    state.pendingExportPath.reset();
    ImGui::CloseCurrentPopup();
    startExport(state, path, resolution, cells);
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0)) || keyPressed(state, GLFW_KEY_ESCAPE)) {
    state.pendingExportPath.reset();
    ImGui::CloseCurrentPopup();
  }
  if (!state.pendingExportPath) retireEstimate(state);
  ImGui::EndPopup();
}

// The import dialog: the chosen file's unit and up axis, then import or cancel.
void importDialog(EditorState& state) {
  const char* title = "Import mesh: options###import options";
  if (state.pendingImport && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  centreNext();
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  if (!state.pendingImport) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  PendingImport& import = *state.pendingImport;
  // Long lines (a path, a reader's error) wrap: the dialog ran off the window's edge with a
  // truncated STL's error cut off (an artist's test).
  ImGui::PushTextWrapPos(ImGui::GetFontSize() * 36.0f);
  ImGui::TextWrapped("%s", import.path.c_str());
  const auto& units = importUnits();
  ImGui::SetNextItemWidth(220);
  if (ImGui::BeginCombo("file unit", units[size_t(import.unit)].label)) {
    for (int i = 0; i < int(units.size()); ++i)
      if (ImGui::Selectable(units[size_t(i)].label, i == import.unit)) import.unit = i;
    ImGui::EndCombo();
  }
  std::string why;
  const double scale = importScale(import.unit, state.document.scene().settings.unit, &why);
  ImGui::TextDisabled("scene unit: %s; scale %.6g", state.document.scene().settings.unit.c_str(),
                      scale);
  if (!why.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", why.c_str());
    ImGui::PopStyleColor();
  }
  const char* upAxes[] = {"+Z up (as written)", "+Y up (turn +Y to +Z)"};
  ImGui::SetNextItemWidth(220);
  ImGui::Combo("up axis", &import.upAxis, upAxes, 2);
  // Its size as the file has it and as it will stand in the scene (an artist's bunny came in
  // 8 mm long and on its side with nothing said): the file read off the UI thread, once.
  if (state.importSizePath != import.path) {
    state.importSizePath = import.path;
    // Read as the import reads it (open meshes taken, to say what keeps them from being closed).
    state.importSizeJob =
        std::make_unique<BackgroundJob<ImportProbe>>([path = import.path](Progress& progress) {
          MeshReadOptions options;
          options.allowOpen = true;
          options.progress = &progress;
          MeshReadReport report;
          ImportProbe probe;
          probe.bounds = meshBounds(readMeshFile(path, options, &report));
          probe.openProblem = report.openProblem;
          return probe;
        });
  }
  const BackgroundJob<ImportProbe>* size = state.importSizeJob.get();
  const bool read = size && size->done() && size->error().empty() && !size->result().bounds.empty();
  const bool open = read && !size->result().openProblem.empty();
  if (read) {
    const glm::dvec3 file = size->result().bounds.size();
    // +Y up turns the file's y onto z and its z onto -y.
    const glm::dvec3 scene =
        scale * (import.upAxis == 1 ? glm::dvec3(file.x, file.z, file.y) : file);
    const char* unit = unitSymbol(state.document.scene().settings.unit);
    ImGui::TextDisabled("in the file: %.4g x %.4g x %.4g", file.x, file.y, file.z);
    ImGui::Text("in the scene: %.4g x %.4g x %.4g %s (x, y, z; z up)", scene.x, scene.y, scene.z,
                unit);
  } else if (size && size->done()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.5f, 0.45f, 1.0f));
    ImGui::TextWrapped("%s", size->error().empty() ? "no triangles" : size->error().c_str());
    ImGui::PopStyleColor();
  } else {
    ImGui::TextDisabled("reading its size...");
  }
  if (import.placement)
    ImGui::TextDisabled("placed where it was dropped (%.4g, %.4g, %.4g)%s",
                        import.placement->point.x, import.placement->point.y,
                        import.placement->point.z,
                        import.placement->onGround ? ", on the ground" : "");
  // An open mesh (holes, a fin, a flipped patch) is taken only when the artist says so: its
  // inside is guessed where rays pass through its holes, so the result may leak.
  if (open) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    ImGui::TextWrapped(
        "Not a closed surface: %s. Its inside is guessed where rays pass its "
        "holes, so parts made with it may leak; closing it first (e.g. in "
        "MeshLab) gives an exact result.",
        size->result().openProblem.c_str());
    ImGui::PopStyleColor();
    ImGui::Checkbox("import it anyway (the scene marks it open)", &import.acceptOpen);
  }
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  // A file that could not be read cannot be imported, nor an open one not accepted: said above,
  // the button off.
  const bool unreadable = (size && size->done() && !read) || (open && !import.acceptOpen);
  ImGui::BeginDisabled(unreadable);
  const bool importNow =
      ImGui::Button("Import", ImVec2(120, 0)) || (!unreadable && keyPressed(state, GLFW_KEY_ENTER));
  ImGui::EndDisabled();
  if (importNow) {
    state.lastImportUnit = import.unit;
    state.lastImportUpAxis = import.upAxis;
    rememberImportChoices(state);
    PendingImport chosen = import;
    state.pendingImport.reset();
    importMesh(state, chosen);
    ImGui::CloseCurrentPopup();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(120, 0)) || keyPressed(state, GLFW_KEY_ESCAPE)) {
    state.pendingImport.reset();
    ImGui::CloseCurrentPopup();
  }
  if (!state.pendingImport) {  // imported or cancelled: the size is not needed any more
    state.importSizeJob.reset();
    state.importSizePath.clear();
  }
  ImGui::EndPopup();
}

}  // namespace

void drawModals(EditorState& state) {
  auto& retired = state.retiredEstimates;  // those that have stopped go
  retired.erase(
      std::remove_if(retired.begin(), retired.end(),
                     [](const std::unique_ptr<ExportEstimateJob>& job) { return job->done(); }),
      retired.end());
  auto& measures = state.retiredPartMeasures;  // the same for the selection's measures
  measures.erase(
      std::remove_if(measures.begin(), measures.end(),
                     [](const std::unique_ptr<PartMeasureJob>& job) { return job->done(); }),
      measures.end());
  viewContextMenu(state);
  recoveryQuestion(state);
  overwriteQuestion(state);
  unsavedQuestion(state);
  quitDuringExportQuestion(state);
  importDialog(state);
  exportOptionsDialog(state);
  exportWindow(state);
}

}  // namespace strata::ui
