// The 3D view in the middle of the editor: camera navigation, click-to-select, the gizmo, the
// section plane, drops from the palette, and drawing the scene through ViewportRenderer.
// Clicks and drops are resolved against what is on screen (ViewportRenderer::pick: the leaf and
// the point under the cursor), whichever way the splats reached GL.
//
// Navigation: orbit with the middle mouse button (or Alt + left), pan with Shift + middle, zoom
// with the wheel (about the surface under the cursor); F frames the selection, Home shows
// everything, 1 / 3 / 7 look from the front, right, top (Ctrl: back, left, bottom), 5 toggles
// orthographic; W / E / R pick move, rotate, scale. Input is taken only when ImGui does not want
// it.
//
// Threads: the UI thread.
#pragma once

#include <optional>
#include <vector>

#include "engine/util/timer.h"
#include "ui/camera.h"
#include "ui/editor_state.h"
#include "ui/gizmo.h"
#include "ui/pattern_guides.h"
#include "ui/resize_gesture.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

// A rectangle of the window in window coordinates (ImGui's: pixels, origin top-left).
struct ViewRect {
  double x = 0.0, y = 0.0, width = 1.0, height = 1.0;
};

// `rect` in the framebuffer's pixels (GL's origin, bottom left): the x, y, width and height
// of the frame the view draws into, `pixelScale` framebuffer pixels per window pixel.
void viewPixels(const ViewRect& rect, int framebufferHeight, double pixelScale, int* x, int* y,
                int* width, int* height);

class Viewport {
 public:
  Camera camera;

  void handleInput(EditorState& state, const ViewRect& rect);
  // Resolves this frame's click (selection) and palette drop (a new node on the surface under
  // the cursor, or on the ground plane) with `renderer`. After handleInput, before draw.
  void resolvePicks(ViewportRenderer& renderer, EditorState& state, const ViewRect& rect,
                    double pixelScale);
  // What the view shows at `mouse` (window pixels from the view's top-left corner).
  std::optional<PickHit> pickAt(ViewportRenderer& renderer, const EditorState& state,
                                const ViewRect& rect, glm::dvec2 mouse, double pixelScale);
  // Where a palette item dropped at `mouse` goes (see Placement).
  Placement placementAt(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
                        glm::dvec2 mouse, double pixelScale);
  // Draws into the bound framebuffer of `framebufferHeight` pixels, `pixelScale` framebuffer
  // pixels per window pixel. With `lastFrameMs` >= 0 (the editor's window), within the frame
  // budget through the renderer's cached image (drawCached); otherwise every splat at once
  // (screenshots, headless renders).
  void draw(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
            int framebufferHeight, double pixelScale, double lastFrameMs = -1.0);
  // draw in two steps, for a frame that may leave the view as it is: prepare makes the frame's
  // camera, lines and overlay (and the renderer's backdrop) and says whether the window already
  // shows them (ViewportRenderer::windowShows); drawPrepared then draws them like draw.
  bool prepare(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
               int framebufferHeight, double pixelScale);
  void drawPrepared(ViewportRenderer& renderer, double lastFrameMs);
  // The prepared view drawn again within `clip` (window pixels) where the window keeps it
  // (ViewportRenderer::repaintWindow).
  void repaintPrepared(ViewportRenderer& renderer, const PixelRect& clip) const;
  // The measurements' labels (measure_tool.h), in this frame's ImGui draw lists.
  void drawAnnotations(const EditorState& state, const ViewRect& rect);
  // Frame the whole scene / the selection (at the next handleInput or draw).
  void viewAll(const EditorState& state);
  // After an edit (not during a drag or a held widget) that grew the result around the camera,
  // which was outside it before: frames the whole scene and says so, since the view then shows
  // nothing but the inside of a part. Call once a frame, after handleInput.
  void keepCameraOutside(EditorState& state);
  void frameSelected(const EditorState& state);
  // After an edit that added the selection (EditorState::revealSelection): where any corner of
  // its box lies outside the view in `rect`, the camera moves out at once to show the box and
  // what it showed around its target (not the whole scene: an artist zoomed onto a detail stays
  // near it), and says so; false where it was in view already (the view as it is). Clears the
  // request.
  bool revealSelection(EditorState& state, const ViewRect& rect);
  // Orthographic <-> perspective (at the next handleInput or draw): Camera::setOrtho, keeping the
  // whole scene in view where it was.
  void toggleOrtho(const EditorState& state);
  bool gizmoDragging() const { return gizmo_.dragging(); }
  // Where the gizmo sits: on the primary selected node (its parent's world matrix and its
  // transform), or, with several parts selected and the pivot at the selection's centre (or an
  // instance), on a pivot there (world axes; *pivot set). False when nothing is selected.
  bool gizmoPlacement(const EditorState& state, glm::dmat4* parentWorld, Transform* transform,
                      bool* pivot);

 private:
  ScreenMapping mapping(const EditorState& state, const ViewRect& rect) const;
  ViewportFrame makeFrame(const EditorState& state, const ViewRect& rect, int framebufferHeight,
                          double pixelScale) const;
  double sceneRadius(const EditorState& state) const;
  bool placeGizmo(const EditorState& state);
  struct PendingClick {
    glm::dvec2 mouse;  // window pixels from the view's top-left corner
    bool extend = false;
  };
  // A rectangle dragged over the view from empty space: box selection on release.
  struct PendingBox {
    glm::dvec2 from, to;  // window pixels from the view's top-left corner
    bool extend = false;  // Shift or Ctrl: add to the selection
  };
  // A palette item dragged over the view: where to look up the part under the pointer.
  std::optional<glm::dvec2> dropHover_;
  Stopwatch dropHoverClock_;
  static constexpr double kDropHoverSeconds = 0.1;
  struct PendingDrop {
    glm::dvec2 mouse;
    int item = 0;                     // palette item: a NodeKind, or kImportMeshItem
    PlaceMode mode = PlaceMode::Add;  // with the modifiers held at the release (dropMode)
  };

  // Framing waits for the viewport's shape, known in handleInput and draw.
  // Also where the view changed shape since the last frame (Camera::reshape).
  void framePending(const ViewRect& rect, const EditorState& state);
  double lastAspect_ = 0.0;  // the view's width / height at the last frame; 0 before the first
  ViewReshape reshape_;
  void handleKeys(EditorState& state);

  // The tree when a gizmo drag began: the other selected nodes follow the primary from it
  // (followingTransforms), all in the drag's one undo step.
  NodePtr dragStart_;
  // keepCameraOutside: the document revision it last looked at, and whether the camera was
  // inside the scene's box then.
  uint64_t cameraCheckedRevision_ = ~uint64_t(0);
  bool cameraWasInside_ = false;
  // A drag of the selection's pivot (gizmoPlacement): every selected part moves by the pivot's
  // motion from dragStart_; pivotNow_ is the pivot's transform as dragged so far.
  bool pivotGroup_ = false;
  Transform pivotNow_;
  bool shearSaid_ = false;  // this drag has said a part could not follow it exactly
  bool restSaid_ = false;   // this drag has said a scaled part stays where it rested
  // What a gizmo scale moved with the scaled part `dragResized_`, from where the drag began
  // (followResize): what followed it in the last frame is said when the drag ends.
  ResizeGesture dragGesture_;
  // The boxes of the labels drawAnnotations drew last (view pixels): the drag readout keeps off
  // them.
  std::vector<ScreenBox> labelBoxes_;
  std::vector<FittedParam> dragFitted_;  // what the last frame's size fitted (scaleIntoSize)
  NodeId dragResized_ = 0;

  // The selection box drawn each frame, worked out again only when the document or the
  // selection changes: a mesh leaf's bounds walk all its vertices (sceneBounds remembers its own).
  const Bounds& cachedSelectionBounds(const EditorState& state);
  uint64_t selectionBoundsRevision_ = ~uint64_t(0);
  std::vector<NodeId> selectionBoundsOf_;
  Bounds selectionBounds_;
  // The pattern guides drawn each frame (pattern_guides.h), worked out again likewise: a
  // pattern's bounds go through every copy.
  uint64_t guidesRevision_ = ~uint64_t(0);
  std::vector<NodeId> guidesOf_;
  std::vector<PatternGuide> guides_;

  Gizmo gizmo_;
  std::optional<Bounds> pendingFrame_;
  std::optional<Bounds> pendingOrthoToggle_;  // the scene's bounds when it was asked for
  // What prepare made for drawPrepared.
  struct Prepared {
    ViewportFrame frame;
    std::vector<LineVertex> lines, overlay, triangles;
  } prepared_;
  int hot_ = -1;
  bool navigating_ = false;
  bool clickPending_ = false;
  std::optional<PendingClick> click_;
  // Wheel steps of this frame at `mouse`, zoomed about the surface under it by resolvePicks
  // (Camera::zoomAbout), about the point under it at the target's depth where it shows nothing. The
  // surface point is looked up once for a run of steps: while the cursor stays on its pixel and the
  // camera is as the last zoom left it, the point is still under it (zoomAbout keeps it there).
  struct PendingWheel {
    glm::dvec2 mouse;
    double steps = 0.0;
  };
  std::optional<PendingWheel> wheel_;
  struct WheelPivot {
    glm::dvec2 mouse;
    std::optional<glm::dvec3> point;  // none: the cursor showed nothing
    glm::dvec3 target{0.0};           // the camera the zoom left
    double distance = 0.0;
    double yaw = 0.0, pitch = 0.0;
    bool ortho = false;
  };
  std::optional<WheelPivot> wheelPivot_;
  // A right click on the view: the part under it selected and its menu opened
  // (EditorState::viewContextMenu).
  std::optional<PendingClick> contextClick_;
  std::optional<PendingDrop> drop_;
  std::optional<glm::dvec2> boxFrom_;  // where a box selection being dragged began
  std::optional<PendingBox> box_;
};

// The section plane of `state` over the scene's bounds: unit normal and offset (what lies where
// dot(normal, p) > offset is cut away). False when it is off or the scene is empty.
bool sectionPlane(const EditorState& state, glm::dvec3* normal, double* offset);

// Where `section` lies along its axis (scene units) in a scene of bounds `scene` (not empty): its
// place once placed, else the fraction `startFraction` of the bounds.
double sectionAt(const SectionState& section, const Bounds& scene);

// Fixes the section plane of `state` in the scene where it now lies, when it is on, not yet
// placed and the scene has parts: from then on it stays there as parts move. Each frame.
void placeSection(EditorState& state);

}  // namespace strata::ui
