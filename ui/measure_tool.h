// The measure tool (M): clicks on the preview place the points of the document's measurements
// (engine/document/measurement.h). Two clicks measure a distance (shown with its dx, dy, dz in
// scene units); a third click, before Esc, turns it into the angle at the second point. A click
// snaps to the nearest corner or edge midpoint of the clicked part's own box (its frame's
// bounding box, so a turned box's corners are its corners) within kMeasureSnapPixels, on a
// section's cap to the cap's nearest edge, else takes the surface point the view shows (a splat,
// or the section's cap). The measurements stay
// on screen until removed (Diagnostics, or Edit > Clear measurements) and follow their parts.
//
// Threads: the UI thread.
#pragma once

#include <glm/vec2.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/document/measurement.h"
#include "ui/gizmo.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

struct EditorState;

constexpr double kMeasureSnapPixels = 10.0;

struct MeasureTool {
  bool active = false;
  std::optional<MeasurePoint> first;  // the first point of a distance being placed
  glm::dvec3 firstWorld{0.0};         // where it was when placed (its part may go meanwhile)
  // The measurement that a third click turns into an angle: its index, valid while the
  // document is still at `openRevision` (an undo or any other edit closes it).
  int open = -1;
  uint64_t openRevision = 0;
  std::string lastSnap;  // what the last click snapped to, for the viewport's hint
};

// Where a click at `mouse` (view pixels) on `hit` measures from: of the corners and edge
// midpoints of the part's box within kMeasureSnapPixels on screen that lie on the surface the
// view shows (`shown(p)`: the view shows a surface point within a couple of cells of p at p's
// pixel: a cutter's corner in the air above the part, or a cylinder's box corner beside it, is
// not taken), the nearest to the hit in the world (the one in front, not one behind on the same
// line of sight), else the hit itself. *what says which ("corner", "edge midpoint", "section
// cap", "surface").
// On the section's cap, `capEdge` (PickWindow::capEdgeNear: the cap's drawn side within
// kMeasureSnapPixels), when there is one, comes first (as drawn: to about a cell): two clicks near
// a wall's sides in a section measure its thickness.
glm::dvec3 snapMeasurePoint(const EditorState& state, const ScreenMapping& view, const PickHit& hit,
                            glm::dvec2 mouse, const std::function<bool(const glm::dvec3&)>& shown,
                            std::string* what = nullptr,
                            const std::optional<glm::dvec3>& capEdge = std::nullopt);
// A click of the tool at `world` on leaf `leaf` (0: none): the first point, the second (a
// distance, one undo step) or the third (an angle, one more).
void measureClick(EditorState& state, uint32_t leaf, const glm::dvec3& world);
// Esc: drops the point being placed and closes the open measurement; with neither, leaves the
// tool.
void measureEscape(EditorState& state);
void setMeasuring(EditorState& state, bool on);
void removeMeasurement(EditorState& state, size_t index);
void clearMeasurements(EditorState& state);

// "42.5 mm", and "dx 30 mm  dy -29.5 mm  dz 0 mm", "90.0 deg" for people.
std::string distanceText(const EditorState& state, double distance);
std::string measureSummary(const EditorState& state, const MeasureValues& v);

// The measurements' segments and point markers (overlay lines, drawn over the scene).
void appendMeasureLines(const EditorState& state, const ScreenMapping& view,
                        std::vector<LineVertex>* overlay);
// Their labels, at the segments' midpoints and the angles' vertices, into ImGui's background
// draw list of the frame; (x0, y0) is the view's top-left corner in window pixels.
// `keepClear`: boxes of the view the labels stay off (the gizmo's, Gizmo::screenBox), in the
// view's pixels.
// Returns `keepClear` with the boxes of the labels drawn added (view pixels), for what is drawn
// after them (the gizmo drag's readout).
std::vector<ScreenBox> drawMeasureLabels(const EditorState& state, const ScreenMapping& view,
                                         double x0, double y0,
                                         const std::vector<ScreenBox>& keepClear = {});

// The view's first line of text (its name and tool) ends this far below its top (pixels); the
// tool's hint takes the line below it. Labels drawn over the view stay under both.
constexpr double kViewTextTop = 26.0;

// Where a label whose box is `box` goes in the view [viewLo, viewHi): moved whole into the view
// (a label near its edge read "12.4" for "12.45 mm"), then to the nearest position `step` pixels
// at a time down or up (down first, at most 32 steps each way) where it covers none of `taken`
// (the labels drawn before it, the gizmo), still in the view; where there is none, where it was
// moved into the view.
ScreenBox placedLabelBox(ScreenBox box, const std::vector<ScreenBox>& taken, glm::dvec2 viewLo,
                         glm::dvec2 viewHi, double step);

// Where the label of the on-screen segment a-b goes, the label's half-size `half` (all pixels,
// y down): on the segment's middle, or, where the label would cover an end's marker (a segment
// shorter than its label: it hid the whole line), beside the segment, clear of the line through
// it and of the markers, on its upper side.
glm::dvec2 measureLabelCentre(glm::dvec2 a, glm::dvec2 b, glm::dvec2 half);

}  // namespace strata::ui
