// The preview panel (resolution), the status bar and the diagnostics window.
#include <imgui.h>

#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/document/commands.h"
#include "engine/eval/evaluator.h"
#include "engine/ldi/grid.h"
#include "engine/util/error.h"
#include "ui/editor_actions.h"
#include "ui/import_options.h"
#include "ui/panels.h"
#include "ui/scene_queries.h"
#include "ui/text_fit.h"
#include "ui/typed_value.h"
#include "ui/viewport.h"

namespace strata::ui {
namespace {

std::string bytesText(double bytes) {
  char text[64];
  if (bytes >= 1024.0 * 1024.0 * 1024.0)
    std::snprintf(text, sizeof(text), "%.2f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  else if (bytes >= 1024.0 * 1024.0)
    std::snprintf(text, sizeof(text), "%.1f MiB", bytes / (1024.0 * 1024.0));
  else
    std::snprintf(text, sizeof(text), "%.0f KiB", bytes / 1024.0);
  return text;
}

std::string countText(uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// The grid an evaluation at `resolution` would use, remembered per document revision; false
// with *why (the reason none does: an empty scene, one too large to measure) otherwise.
bool gridAt(const EditorState& state, int resolution, Grid* grid, std::string* why) {
  static uint64_t revision = ~uint64_t(0);
  static int cachedResolution = 0;
  static bool ok = false;
  static Grid cached;
  static std::string reason;
  if (revision != state.document.revision() || cachedResolution != resolution) {
    revision = state.document.revision();
    cachedResolution = resolution;
    try {
      cached = Evaluator::gridFor(state.document.scene(), resolution);
      ok = true;
      reason.clear();
    } catch (const Error& e) {
      ok = false;
      reason = e.what();
    }
  }
  *grid = cached;
  *why = reason;
  return ok;
}

// Root LDI bytes at `resolution`: scaled from the shown result (surfels grow with the square of
// the resolution), or a guess of two surfels per ray when nothing is shown yet.
double estimateBytes(const EditorState& state, const Grid& grid, int resolution) {
  const PreviewResult* shown = state.preview.get();
  if (shown && shown->ok() && shown->resolution > 0) {
    double ratio = double(resolution) / shown->resolution;
    return double(shown->ldiBytes) * ratio * ratio;
  }
  double rays = double(grid.rayCount(0) + grid.rayCount(1) + grid.rayCount(2));
  return rays * (2.0 * sizeof(Surfel) + sizeof(uint32_t));
}

}  // namespace

namespace {

// A slider's grab half transparent, so that the number drawn over it stays readable (an artist:
// the grab covered a digit). Pop with ImGui::PopStyleColor(2).
void pushTranslucentGrab() {
  for (ImGuiCol col : {ImGuiCol_SliderGrab, ImGuiCol_SliderGrabActive}) {
    ImVec4 color = ImGui::GetStyleColorVec4(col);
    color.w *= 0.45f;
    ImGui::PushStyleColor(col, color);
  }
}

// The steps up to `hi`, coarse to fine.
std::vector<int> resolutionSteps(int hi) {
  std::vector<int> steps;
  for (int p = 1; p <= hi; p *= 2) {
    steps.push_back(p);
    if (p >= 2 && p + p / 2 <= hi) steps.push_back(p + p / 2);
  }
  std::sort(steps.begin(), steps.end());
  return steps;
}

}  // namespace

int resolutionStepNearest(int resolution) {
  if (resolution <= 1) return 1;
  int best = 1;
  for (int step : resolutionSteps(2 * resolution)) {
    const double distance = std::abs(std::log(double(step) / resolution));
    const double bestDistance = std::abs(std::log(double(best) / resolution));
    if (distance < bestDistance - 1e-12) best = step;
  }
  return best;
}

int resolutionStepAfter(int resolution, int direction, int lo, int hi) {
  int result = resolution;
  if (direction > 0) {
    for (int step : resolutionSteps(2 * std::max(resolution, 1)))
      if (step > resolution) {
        result = step;
        break;
      }
  } else {
    for (int step : resolutionSteps(resolution))
      if (step < resolution) result = step;
  }
  return std::clamp(result, lo, hi);
}

void drawPreviewPanel(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(
      ImVec2(vp->Pos.x + vp->Size.x - layout.rightWidth,
             vp->Pos.y + vp->Size.y - layout.statusHeight - layout.previewHeight));
  ImGui::SetNextWindowSize(ImVec2(layout.rightWidth, layout.previewHeight));
  ImGui::Begin("Preview", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus);
  const Scene& scene = state.document.scene();
  int resolution = scene.settings.resolution;
  ImGui::TextUnformatted("resolution");
  ImGui::SameLine(90.0f);
  // The slider, then - and + (one step coarser or finer each).
  const float button = ImGui::GetFrameHeight();
  const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
  ImGui::SetNextItemWidth(-2.0f * (button + spacing));
  const int before = resolution;
  pushTranslucentGrab();
  bool changed = ImGui::SliderInt("##resolution", &resolution, 16, kSliderMaxResolution, "%d cells",
                                  ImGuiSliderFlags_Logarithmic);
  ImGui::PopStyleColor(2);
  changed = commitTypedValue(changed, &resolution);  // "512" never evaluates 16 (from "5")
  // Dragged (not typed), the slider lands on the steps: 20 pixels apart rather than a cell every
  // pixel or two (an artist's 40-pixel drag went from 256 to 117 cells).
  if (changed && ImGui::IsItemActive()) resolution = resolutionStepNearest(resolution);
  if (ImGui::IsItemActivated()) state.document.beginInteraction();
  // A typed value out of range is refused with the range, not clamped (16384 cells clamped from
  // an artist's 100000 was saved into the scene).
  if (changed) setResolution(state, resolution);
  if (ImGui::IsItemDeactivated()) state.document.endInteraction();
  // A double-click types a number, as on the inspector's fields, from the resolution its first
  // press jumped from.
  double beforePress = 0.0;
  if (doubleClickOpensTyping(before, &beforePress)) setResolution(state, int(beforePress));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Cells along the longest side of the grid. Dragging steps through\n"
        "16, 24, 32, 48 ... 1024 and shows a coarse preview at once; it refines\n"
        "when you let go. Double-click or Ctrl+click to type any number\n"
        "(Enter applies it, Esc keeps the old one).");
  for (int direction : {-1, +1}) {
    ImGui::SameLine(0.0f, spacing);
    const int next = resolutionStepAfter(scene.settings.resolution, direction, 16,
                                         std::max(kSliderMaxResolution, scene.settings.resolution));
    ImGui::BeginDisabled(next == scene.settings.resolution);
    if (ImGui::Button(direction < 0 ? "-##coarser" : "+##finer", ImVec2(button, button)))
      setResolution(state, next);
    ImGui::EndDisabled();
    // At the end of the range the button is off and says so (it offered "Finer: 1024 cells" at
    // 1024: an artist's re-test).
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
      if (next == scene.settings.resolution)
        ImGui::SetTooltip(direction < 0 ? "%d cells: the coarsest step"
                                        : "%d cells: the finest step (double-click the field to "
                                          "type more)",
                          next);
      else
        ImGui::SetTooltip(direction < 0 ? "Coarser: %d cells" : "Finer: %d cells", next);
    }
  }
  // The grid of the preview shown where it is this resolution's full pass (the preview keeps its
  // lattice while parts move: Evaluator::previewGridFor), so that the panel and the status bar
  // name the same cells; else the grid an evaluation from scratch would use.
  // While a drag shows drafts, the last full pass's grid (the one the drag's release refines on).
  static Grid lastFullGrid;
  static int lastFullResolution = 0;
  const PreviewResult* shown = state.preview.get();
  if (!shown) lastFullResolution = 0;  // a document opened (replaceDocument): nothing shown yet
  if (shown && shown->ok() && !shown->coarse) {
    lastFullGrid = shown->stats.grid;
    lastFullResolution = shown->resolution;
  }
  // Only while it still holds the scene (not another document's, nor an empty scene's).
  const Bounds parts = sceneBounds(state.document.root());
  const Bounds held = lastFullGrid.bounds();
  Grid grid;
  const bool shownGrid = lastFullResolution == scene.settings.resolution && !parts.empty() &&
                         glm::all(glm::greaterThanEqual(parts.min, held.min)) &&
                         glm::all(glm::lessThanEqual(parts.max, held.max));
  if (shownGrid) grid = lastFullGrid;
  // The grid a full pass being evaluated uses (the preview keeps its cells while parts move:
  // the scene's own grid at this resolution said other numbers than the status bar's, which
  // shows the result's, until it came).
  const bool evaluatingGrid = state.worker.busy && state.worker.gridKnown &&
                              state.worker.resolution == scene.settings.resolution;
  if (evaluatingGrid) grid = state.worker.grid;
  std::string noGrid;
  if (shownGrid || evaluatingGrid || gridAt(state, scene.settings.resolution, &grid, &noGrid)) {
    ImGui::Text("cell h = %.4g %s", grid.h, unitSymbol(scene.settings.unit));
    ImGui::Text("grid %d x %d x %d", grid.cells.x, grid.cells.y, grid.cells.z);
    const int longest = std::max(grid.cells.x, std::max(grid.cells.y, grid.cells.z));
    if (ImGui::IsItemHovered() && longest != scene.settings.resolution)
      ImGui::SetTooltip(
          "%d cells along the longest side, not %d: the preview keeps its cells while parts\n"
          "move (within an eighth of the size asked for), so that what did not change is\n"
          "not evaluated again.",
          longest, scene.settings.resolution);
    ImGui::Text("root LDI ~ %s",
                bytesText(estimateBytes(state, grid, scene.settings.resolution)).c_str());
    if (state.previewCappedAt > 0) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.35f, 1.0f));
      ImGui::TextWrapped(
          "preview at %d cells: %d would not fit in memory or take too long to preview "
          "(an export tiles, and estimates first)",
          state.previewCappedAt, scene.settings.resolution);
      ImGui::PopStyleColor();
    }
    // What the evaluation said about parts too small or too thin for the cell size: counted
    // here, said in full at the panel's end (in full here, it pushed the gizmo's mode and pivot
    // out of the panel: an artist's test).
    if (!state.fullPassWarnings.empty()) {
      const size_t n = state.fullPassWarnings.size();
      ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.35f, 1.0f), "%zu %s (below; hover to read)", n,
                         n == 1 ? "warning" : "warnings");
      // Read where the count is: in a short panel they sat out of sight below the gizmo's
      // settings (an artist's test); a click opens Diagnostics, which lists them with the rest.
      if (ImGui::IsItemHovered()) {
        ImGui::BeginTooltip();
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
        for (const std::string& w : state.fullPassWarnings) ImGui::TextUnformatted(w.c_str());
        ImGui::TextDisabled("click: View > Diagnostics");
        ImGui::PopTextWrapPos();
        ImGui::EndTooltip();
      }
      if (ImGui::IsItemClicked()) state.showDiagnostics = true;
    }
  } else {
    // Why no grid holds the scene (empty, or too large or small to measure), wrapped.
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("no grid: %s", noGrid.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::Separator();
  // The section plane: a view setting, cut and capped on the GPU as the splats are drawn.
  ImGui::Checkbox("section", &state.section.on);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Cut the preview with a plane across one axis and cap the cut");
  ImGui::BeginDisabled(!state.section.on);
  const char* axes[] = {"x", "y", "z"};
  ImGui::SameLine();
  ImGui::SetNextItemWidth(50.0f);
  // Another axis: the plane starts again in the middle of the scene along it.
  if (ImGui::Combo("##sectionAxis", &state.section.axis, axes, 3)) {
    state.section.at.reset();
    state.section.startFraction = 0.5;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The axis the section plane lies across");
  ImGui::SameLine();
  ImGui::Checkbox("flip", &state.section.flip);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Cut away the other side of the plane");
  ImGui::SetNextItemWidth(-1);
  // The plane's place in scene units along its axis. It is placed (fixed in the scene) the first
  // time it is shown, so that it stays where it is as parts move; the slider spans the scene's
  // bounds, and the plane's place where it lies outside them.
  const Bounds bounds = sceneBounds(state.document.root());
  const int axis = std::clamp(state.section.axis, 0, 2);
  placeSection(state);
  double where = state.section.at ? *state.section.at : 0.0;
  const double lo = std::min(where, bounds.empty() ? 0.0 : bounds.min[axis]);
  const double hi = std::max(where, bounds.empty() ? 1.0 : bounds.max[axis]);
  const double whereBefore = where;
  // "at x = %.4g mm": ImGui formats the value, and its text field (Ctrl+click, double-click)
  // shows the number alone.
  std::string sliderFormat = std::string("at ") + axes[axis] + " = %.4g ";
  for (const char* c = unitSymbol(scene.settings.unit); *c; ++c)
    sliderFormat += *c == '%' ? std::string("%%") : std::string(1, *c);
  pushTranslucentGrab();
  const bool movedSection = ImGui::SliderScalar("##sectionAt", ImGuiDataType_Double, &where, &lo,
                                                &hi, sliderFormat.c_str());
  ImGui::PopStyleColor(2);
  // A typed place is kept as typed, even outside the scene's bounds.
  if (commitTypedValue(movedSection, &where) && std::isfinite(where)) state.section.at = where;
  // A double-click types a number here too, at the plane's place before the first press moved it.
  double planeBeforePress = 0.0;
  if (doubleClickOpensTyping(whereBefore, &planeBeforePress)) state.section.at = planeBeforePress;
  if (ImGui::IsItemHovered() && !ImGui::IsItemActive())
    ImGui::SetTooltip("Drag to move the plane; double-click or Ctrl+click to type where");
  ImGui::EndDisabled();
  ImGui::Checkbox("ground grid", &state.showGrid);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The grid on z = 0; its spacing follows the scene's size (the move step)");
  ImGui::SameLine();
  ImGui::Checkbox("snap", &state.snap.enabled);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Gizmo snapping: move step, 15\u00B0, scale 0.1");
  // The move step follows the ground grid shown unless a step is typed.
  const std::string stepFormat = std::string("%.3g ") + unitSymbol(scene.settings.unit);
  ImGui::SetNextItemWidth(100.0f);
  numberFieldNext("move step");
  // The field applies each keystroke: what is typed is judged when the field is left (a step of
  // 0 or less was clamped to 1e-09 without a word, and Ctrl+D then put copies on their originals).
  static double stepBefore = 0.0, stepTyped = 0.0;  // UI thread only: the typing in this field
  const double stepShown = state.snap.step;
  const bool stepEdited =
      ImGui::InputDouble("move step", &state.snap.step, 0.0, 0.0, stepFormat.c_str());
  if (ImGui::IsItemActivated()) stepBefore = stepTyped = stepShown;
  if (stepEdited) stepTyped = state.snap.step;
  // "1cm": 10 mm; "3 xyz": the step it had.
  if (convertLengthTypedIntoInput(&stepTyped, unitSymbol(scene.settings.unit)) ==
      TypedUnit::Refused)
    stepTyped = stepBefore;
  if (ImGui::IsItemDeactivated()) {
    if (const std::string converted = takeUnitConversion(); !converted.empty())
      logInfo(state, "typed " + converted);
    if (stepTyped > 0.0 && std::isfinite(stepTyped)) {
      // A step typed no longer follows the grid (Escape, which puts the step back, keeps it).
      if (stepTyped != stepBefore) state.snapFollowsGrid = false;
      state.snap.step = stepTyped;
    } else {
      state.snap.step = stepBefore;
      char text[128];
      std::snprintf(text, sizeof(text), "the move step must be greater than 0: it stays %.4g %s",
                    stepBefore, unitSymbol(scene.settings.unit));
      logWarning(state, text);
    }
  }
  state.snap.step = std::max(state.snap.step, 1e-9);  // while a 0 is being typed
  ImGui::SameLine();
  if (ImGui::Checkbox("= grid", &state.snapFollowsGrid) && state.snapFollowsGrid)
    state.snap.step = groundGridStep(sceneBounds(state.document.root()),
                                     emptySceneSpan(state.document.scene().settings.unit));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("The move step is the ground grid's spacing, which follows the scene's size");
  const char* modes[] = {"move (W)", "rotate (E)", "scale (R)"};
  int mode = int(state.gizmoMode);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::Combo("##gizmo", &mode, modes, 3)) state.gizmoMode = GizmoMode(mode);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("What the gizmo on the selection does: move (W), rotate (E), scale (R)");
  const char* pivots[] = {"pivot: selection centre", "pivot: active part"};
  int pivot = state.pivotAtSelectionCentre ? 0 : 1;
  ImGui::SetNextItemWidth(-1);
  if (ImGui::Combo("##pivot", &pivot, pivots, 2)) state.pivotAtSelectionCentre = pivot == 0;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "With several parts selected, what the gizmo turns and scales them about:\nthe centre "
        "of their box (world axes), or the origin of the part clicked last (its axes)");
  if (noGrid.empty() && !state.fullPassWarnings.empty()) {
    const auto& warnings = state.fullPassWarnings;
    ImGui::Separator();
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.35f, 1.0f));
    for (size_t i = 0; i < warnings.size() && i < 3; ++i)
      ImGui::TextWrapped("%s", warnings[i].c_str());
    if (warnings.size() > 3)
      ImGui::TextWrapped("and %zu more (View > Diagnostics)", warnings.size() - 3);
    ImGui::PopStyleColor();
  }
  ImGui::End();
}

namespace {

// The message the status bar shows: the latest message while it is new (an error until clicked
// away or settled, the others for 6 s); null for none. An
// error older than a later message is not shown again in its place (an artist read a refusal
// coming back after a successful undo as the undo's failure): it is counted beside it, and on
// its own once that message has gone (drawStatusBar).
LogLine* statusLine(EditorState& state) {
  if (state.log.empty()) return nullptr;
  LogLine& last = state.log.back();
  if ((last.level == LogLevel::Error && !last.dismissed) || state.now - last.time < 6.0)
    return &last;
  return nullptr;
}

// Errors not yet clicked away besides `shown`.
int otherOpenErrors(const EditorState& state, const LogLine* shown) {
  int count = 0;
  for (const LogLine& line : state.log)
    count += line.level == LogLevel::Error && !line.dismissed && &line != shown ? 1 : 0;
  return count;
}

}  // namespace

void drawStatusBar(EditorState& state, const PanelLayout& layout) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x, vp->Pos.y + vp->Size.y - layout.statusHeight));
  ImGui::SetNextWindowSize(ImVec2(vp->Size.x, layout.statusHeight));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::TextDisabled("%s", state.backendDescription.c_str());
  // What the user must read comes first, so that a narrow window cuts the figures, not it: the
  // preview's error or the latest message, and the evaluation under way.
  if (!state.previewError.empty()) {
    ImGui::SameLine();
    const std::string fitted =
        fitWithEllipsis("|  " + state.previewError, ImGui::GetContentRegionAvail().x,
                        [](const std::string& s) { return ImGui::CalcTextSize(s.c_str()).x; });
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", fitted.c_str());
    if (ImGui::IsItemHovered() && fitted.size() != state.previewError.size() + 3) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
      ImGui::TextUnformatted(state.previewError.c_str());
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
  } else if (LogLine* message = statusLine(state)) {
    LogLine& last = *message;
    ImGui::SameLine();
    ImVec4 color = last.level == LogLevel::Error     ? ImVec4(1.0f, 0.4f, 0.4f, 1.0f)
                   : last.level == LogLevel::Warning ? ImVec4(1.0f, 0.8f, 0.3f, 1.0f)
                                                     : ImVec4(0.6f, 0.85f, 0.6f, 1.0f);
    // A message longer than what is left of the bar ends in an ellipsis (it ran off the edge,
    // cut mid-word with nothing to say so: an artist's test); the whole of it on hover.
    const float room = ImGui::GetContentRegionAvail().x;
    const std::string fitted = fitWithEllipsis("|  " + last.text, room, [](const std::string& s) {
      return ImGui::CalcTextSize(s.c_str()).x;
    });
    ImGui::TextColored(color, "%s", fitted.c_str());
    // A message longer than the bar: the whole of it on hover, and a click opens the messages.
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 40.0f);
      ImGui::TextUnformatted(last.text.c_str());
      ImGui::TextDisabled("click: all messages, to read or copy%s",
                          last.level == LogLevel::Error ? " (and clear the errors)" : "");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    bool open = ImGui::IsItemClicked();
    if (const int others = otherOpenErrors(state, &last)) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "(+%d earlier error%s)", others,
                         others == 1 ? "" : "s");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("click: all messages, to read or copy");
      open = open || ImGui::IsItemClicked();
    }
    if (open) {  // the messages show every error: none is left unseen
      state.showDiagnostics = true;
      for (LogLine& line : state.log) line.dismissed = true;
    }
  } else if (const int unread = otherOpenErrors(state, nullptr)) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "|  %d earlier error%s not read", unread,
                       unread == 1 ? "" : "s");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("click: all messages, to read or copy");
    if (ImGui::IsItemClicked()) {
      state.showDiagnostics = true;
      for (LogLine& line : state.log) line.dismissed = true;
    }
  }
  if (state.worker.busy) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "|  evaluating %d%s: %s %.0f%%",
                       state.worker.resolution,
                       state.worker.settling ? " on the export's lattice" : "",
                       state.worker.stage.c_str(), state.worker.fraction * 100.0);
    if (state.worker.settling && ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "While you edit, the preview keeps its lattice so that parts you left alone are not\n"
          "sampled again. At rest it is evaluated on the scene's own lattice: what an export at\n"
          "this resolution, and the document reopened, show.");
  }
  // The figures after the message, each whole or not at all: one cut at the bar's edge
  // ("host upload, 2.7 M") read as a number (an artist's test). Once one does not fit, none
  // after it is drawn.
  bool room = true;
  const auto figure = [&room](const char* format, ...) {
    if (!room) return false;
    char text[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof(text), format, args);
    va_end(args);
    ImGui::SameLine();
    if (ImGui::CalcTextSize(text).x > ImGui::GetContentRegionAvail().x) return room = false;
    ImGui::TextUnformatted(text);
    return true;
  };
  const PreviewResult* shown = state.preview.get();
  if (shown && shown->ok()) {
    const Grid& g = shown->stats.grid;
    figure("|  grid %dx%dx%d  h %.3g %s", g.cells.x, g.cells.y, g.cells.z, g.h,
           unitSymbol(shown->scene->settings.unit));
    figure("|  surfels %s (%s splats, %s, %s)", countText(shown->surfels).c_str(),
           countText(shown->splatCount()).c_str(), state.splatTransfer.c_str(),
           bytesText(double(state.uploadedBytes)).c_str());
    const auto& skipped = shown->stats.skippedModifiers;
    if (figure("|  eval %.0f ms%s", shown->stats.seconds * 1000.0,
               !shown->coarse    ? ""
               : skipped.empty() ? " (coarse)"
                                 : " (coarse, unmodified)") &&
        ImGui::IsItemHovered()) {  // the stages on hover: the bar stays one short line
      ImGui::BeginTooltip();
      if (shown->coarse && !skipped.empty()) {
        std::string names;
        for (const auto& n : skipped) names += (names.empty() ? "" : ", ") + n;
        ImGui::Text("This quick draft leaves out %s:", names.c_str());
        ImGui::Text("smaller than %.0f of its cells, they would tear it. The final image,",
                    kCoarseModifierCells);
        ImGui::Text("coming next, applies them.");
      }
      for (const auto& st : shown->stats.stages)
        ImGui::Text("%-10s %8.1f ms", st.name.c_str(), st.seconds * 1000.0);
      ImGui::EndTooltip();
    }
  }
  figure("|  frame %.1f ms", state.frameMs);
  ImGui::End();
  ImGui::PopStyleVar();
}

namespace {
// The selected part measured alone (one part selected): started in the background for the
// document as it is now, shown once done.
void selectionMeasure(EditorState& state) {
  const NodeId id = state.selection.size() == 1 ? state.selection[0] : 0;
  const NodePtr node = id ? findNode(state.document.root(), id) : nullptr;
  // The part as it is now: the nodes from below the root down to it, unchanged while no edit
  // touched them (an edit elsewhere leaves them shared).
  std::vector<const Node*> path;
  if (node) pathToNode(state.document.root(), id, &path);
  if (!path.empty()) path.erase(path.begin());
  const Transform rootTransform = state.document.root()->transform;
  PartMeasureJob* job = state.partMeasure.get();
  const bool current = job && node && job->id() == id && state.partMeasurePath == path &&
                       state.partMeasureRootTransform == rootTransform;
  // Not while a field is held or the gizmo drags: the part is still changing.
  if (!current && !ImGui::IsAnyItemActive() && !state.document.interacting()) {
    if (state.partMeasure) {
      state.partMeasure->cancel();
      state.retiredPartMeasures.push_back(std::move(state.partMeasure));
    }
    if (node) {
      // At the preview's resolution, at most 512 cells along the part.
      const int resolution =
          std::min(512, state.preview ? state.preview->resolution
                                      : state.document.scene().settings.resolution);
      state.partMeasure = std::make_unique<PartMeasureJob>(
          state.document.snapshot(), id, std::max(resolution, 32), state.makeBackend);
      state.partMeasurePath = path;
      state.partMeasureRootTransform = rootTransform;
    }
  }
  if (!node) return;
  const char* unit = unitSymbol(state.document.scene().settings.unit);
  job = state.partMeasure.get();
  ImGui::Separator();
  if (!job || !job->done()) {
    ImGui::TextDisabled("selection \"%s\": measuring...", node->name.c_str());
    return;
  }
  if (!job->error().empty()) {
    ImGui::TextWrapped("selection \"%s\": not measured (%s)", node->name.c_str(),
                       job->error().c_str());
    return;
  }
  const PartMeasure m = job->result();
  ImGui::TextWrapped("selection \"%s\" alone: volume %.6g %s^3, area %.6g %s^2", node->name.c_str(),
                     m.measure.volume, unit, m.measure.area, unit);
  const Bounds b = selectionBounds(state.document.root(), {id});
  if (!b.empty())
    ImGui::Text("  box of its parts %.4g x %.4g x %.4g %s", b.size().x, b.size().y, b.size().z,
                unit);
  if (std::isfinite(m.measure.thinnestWall))
    ImGui::Text("  thinnest wall about %.4g %s (%.2g cells of %.3g) at (%.4g, %.4g, %.4g)",
                m.measure.thinnestWall, unit, m.measure.thinnestWall / m.h, m.h,
                m.measure.thinnestAt.x, m.measure.thinnestAt.y, m.measure.thinnestAt.z);
}

// The result's extent and the document's measurements (each removable), in scene units.
void measurementList(EditorState& state) {
  const PreviewResult* shown = state.preview.get();
  const char* unit = unitSymbol(state.document.scene().settings.unit);
  if (shown && shown->ok()) {
    const EvalResult& r = shown->stats;
    ImGui::Separator();
    ImGui::Text("result: volume %.6g %s^3, area %.6g %s^2", r.measure.volume, unit, r.measure.area,
                unit);
    if (std::isfinite(r.measure.thinnestWall)) {
      const glm::dvec3 at = r.measure.thinnestAt;
      // Spans under half a cell are not judged (measureLdi): where the warnings name a part
      // thinner than that, this line must not read as the thinnest wall there is (an artist's
      // 0.3 mm shim beside "thinnest wall about 3.9 mm").
      ImGui::TextWrapped(
          "thinnest wall about %.4g %s (%.2g cells) at (%.4g, %.4g, %.4g)%s; walls under half a "
          "cell (%.3g %s) are not judged%s",
          r.measure.thinnestWall, unit, r.measure.thinnestWall / r.grid.h, at.x, at.y, at.z,
          r.measure.thinnestWall < 2.0 * r.grid.h
              ? "; thinner than two cells: raise the resolution to judge it"
              : "",
          0.5 * r.grid.h, unit,
          state.fullPassWarnings.empty() ? "" : " (the warnings below name thinner parts)");
    }
    // The result's own extent, from its splats (the tree's bounds are its parts' boxes: a turned
    // rib's box or a cutter's made it larger than the part an artist measured); once a result,
    // off the UI thread.
    auto& job = state.resultBoundsJob;
    const bool measured = state.resultBoundsOf.lock() == shown->splats;
    if (!measured && (!job || job->done())) {
      state.resultBoundsOf = shown->splats;
      job = std::make_unique<BackgroundJob<Bounds>>(
          [splats = shown->splats](Progress&) { return splatBounds(*splats); });
    }
    if (!measured || !job->done()) {
      ImGui::TextDisabled("bounding box: measuring...");
    } else if (!job->error().empty()) {
      ImGui::TextWrapped("bounding box: not measured (%s)", job->error().c_str());
    } else if (const Bounds b = job->result(); !b.empty()) {
      // A corner within a millionth of the box's size of 0 is at 0 (the splats' float
      // positions put a face on z = 0 at 9.8e-09).
      const double size = std::max({b.size().x, b.size().y, b.size().z});
      const auto zeroed = [&](double v) { return std::fabs(v) <= 1e-6 * size ? 0.0 : v; };
      ImGui::Text("bounding box %.4g x %.4g x %.4g %s (from %.4g, %.4g, %.4g)", b.size().x,
                  b.size().y, b.size().z, unit, zeroed(b.min.x), zeroed(b.min.y), zeroed(b.min.z));
    }
  }
  selectionMeasure(state);
  // A copy: removing one replaces the document's scene.
  const std::vector<Measurement> list = state.document.scene().measurements;
  ImGui::Separator();
  ImGui::Text("measurements (M): %zu", list.size());
  if (!list.empty()) {
    ImGui::SameLine();
    if (ImGui::SmallButton("clear all")) clearMeasurements(state);
  }
  for (size_t i = 0; i < list.size(); ++i) {
    ImGui::PushID(int(i));
    const bool remove = ImGui::SmallButton("x");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Remove this measurement (Ctrl+Z brings it back)");
    ImGui::SameLine();
    const std::string text = measureSummary(state, measureValues(state.document.root(), list[i]));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopID();
    if (remove) {
      removeMeasurement(state, i);
      break;
    }
  }
}
}  // namespace

void drawDiagnostics(EditorState& state) {
  if (!state.showDiagnostics) return;
  ImGui::SetNextWindowSize(ImVec2(560, 460), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowPos(ImVec2(340, 80), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Diagnostics", &state.showDiagnostics)) {
    ImGui::End();
    return;
  }
  ImGui::TextWrapped("backend: %s", state.backendDescription.c_str());
  ImGui::TextWrapped("display: %s", state.glDescription.c_str());
  ImGui::TextWrapped("splats to GL: %s (%.2f ms for the last result, %s)",
                     state.splatTransfer.c_str(), state.uploadMs,
                     bytesText(double(state.uploadedBytes)).c_str());
  const PreviewResult* shown = state.preview.get();
  if (shown && shown->ok()) {
    const EvalResult& r = shown->stats;
    ImGui::Separator();
    ImGui::Text("resolution %d%s, %d computed, %d reused; volume %.6g, area %.6g",
                shown->resolution, shown->coarse ? " (coarse)" : "", r.computed, r.reused,
                r.measure.volume, r.measure.area);
    ImGui::Text("peak memory %s, cache %s, splats %.1f ms", bytesText(double(r.peakBytes)).c_str(),
                bytesText(double(r.cacheBytes)).c_str(), shown->splatSeconds * 1000.0);
    if (ImGui::BeginTable("stages", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
      ImGui::TableSetupColumn("stage");
      ImGui::TableSetupColumn("ms");
      ImGui::TableSetupColumn("nodes");
      ImGui::TableSetupColumn("surfels");
      ImGui::TableHeadersRow();
      for (const auto& s : r.stages) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(s.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.1f", s.seconds * 1000.0);
        ImGui::TableNextColumn();
        ImGui::Text("%d", s.runs);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(countText(s.surfels).c_str());
      }
      ImGui::EndTable();
    }
    if (ImGui::CollapsingHeader("nodes")) {
      if (ImGui::BeginTable("nodes", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                            ImVec2(0, 160))) {
        ImGui::TableSetupColumn("node");
        ImGui::TableSetupColumn("outcome");
        ImGui::TableSetupColumn("ms");
        ImGui::TableSetupColumn("surfels");
        ImGui::TableHeadersRow();
        for (const auto& n : r.nodes) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::Text("%s (%u)", n.name.c_str(), n.id);
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(outcomeName(n.outcome));
          if (n.outcome == NodeOutcome::Merged && ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "Combined in its parent's Boolean: a chain of one operation (a union of\n"
                "unions, a difference of a difference) is evaluated as one Boolean,\n"
                "so this node has no result of its own to time or count.");
          ImGui::TableNextColumn();
          ImGui::Text("%.1f", n.seconds * 1000.0);
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(n.outcome == NodeOutcome::Merged ? "-"
                                                                  : countText(n.surfels).c_str());
        }
        ImGui::EndTable();
      }
    }
  }
  measurementList(state);
  ImGui::Separator();
  ImGui::Text("messages");
  ImGui::SameLine();
  if (ImGui::SmallButton("copy all")) {
    std::string all;
    for (const std::string& w : state.fullPassWarnings) all += "warning: " + w + "\n";
    for (const auto& line : state.log) all += line.text + "\n";
    ImGui::SetClipboardText(all.c_str());
  }
  ImGui::SameLine();
  ImGui::TextDisabled("(click a line to copy it)");
  // The rest of the window, but never fewer than eight lines (below the stages and the nodes it
  // had almost no height: the window scrolls instead).
  const float logHeight =
      std::max(ImGui::GetContentRegionAvail().y, 8.0f * ImGui::GetTextLineHeightWithSpacing());
  ImGui::BeginChild("log", ImVec2(0, logHeight), true);
  // Whole, wrapped; the evaluation's warnings first.
  auto line = [](const ImVec4& color, const std::string& text, int id) {
    ImGui::PushID(id);
    ImGui::PushStyleColor(ImGuiCol_Text, color);
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::PopStyleColor();
    if (ImGui::IsItemClicked()) ImGui::SetClipboardText(text.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("click to copy");
    ImGui::PopID();
  };
  int id = 0;
  for (const std::string& w : state.fullPassWarnings)
    line(ImVec4(1.0f, 0.8f, 0.35f, 1.0f), w, id++);
  for (const auto& entry : state.log) {
    ImVec4 color = entry.level == LogLevel::Error     ? ImVec4(1.0f, 0.45f, 0.45f, 1.0f)
                   : entry.level == LogLevel::Warning ? ImVec4(1.0f, 0.8f, 0.35f, 1.0f)
                                                      : ImVec4(0.8f, 0.8f, 0.8f, 1.0f);
    char when[32];
    std::snprintf(when, sizeof(when), "%7.1f s  ", entry.time);
    line(color, when + entry.text, id++);
  }
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
  ImGui::EndChild();
  ImGui::End();
}

}  // namespace strata::ui
