#include "ui/viewport.h"

#include <imgui.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "engine/document/commands.h"
#include "ui/editor_actions.h"
#include "ui/import_options.h"
#include "ui/measure_tool.h"
#include "ui/panels.h"
#include "ui/resize_followers.h"
#include "ui/scene_queries.h"

namespace strata::ui {
namespace {

void appendBox(const Bounds& b, const glm::vec4& color, std::vector<LineVertex>* lines) {
  glm::dvec3 c[8];
  for (int i = 0; i < 8; ++i)
    c[i] =
        glm::dvec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
  const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                            {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : edges) {
    lines->push_back(lineVertex(c[e[0]], color));
    lines->push_back(lineVertex(c[e[1]], color));
  }
}

// The ground grid in the z = 0 plane around the scene, fading out towards its rim, with the x
// (red) and y (green) axes. Drawn as the renderer's backdrop: never across a part's face.
void appendGrid(const Bounds& scene, double emptySpan, std::vector<LineVertex>* lines) {
  const double step = groundGridStep(scene, emptySpan);
  glm::dvec3 centre = scene.empty() ? glm::dvec3(0.0) : scene.center();
  double cx = std::round(centre.x / step) * step, cy = std::round(centre.y / step) * step;
  const int n = 14;
  for (int i = -n; i <= n; ++i) {
    float fade = float(1.0 - std::abs(i) / double(n + 1));
    double x = cx + i * step, y = cy + i * step;
    bool xAxis = std::fabs(y) < step * 1e-6, yAxis = std::fabs(x) < step * 1e-6;
    glm::vec4 grey(0.62f, 0.64f, 0.68f, 0.28f * fade);
    glm::vec4 ex = xAxis ? glm::vec4(0.90f, 0.30f, 0.32f, 0.75f) : grey;
    glm::vec4 ey = yAxis ? glm::vec4(0.45f, 0.80f, 0.30f, 0.75f) : grey;
    lines->push_back(lineVertex({cx - n * step, y, 0.0}, ex));
    lines->push_back(lineVertex({cx + n * step, y, 0.0}, ex));
    lines->push_back(lineVertex({x, cy - n * step, 0.0}, ey));
    lines->push_back(lineVertex({x, cy + n * step, 0.0}, ey));
  }
}

// The section plane's rectangle across the scene's bounds (grown by a tenth), as lines.
void appendSectionOutline(const EditorState& state, const ViewportFrame& frame,
                          std::vector<LineVertex>* lines) {
  Bounds b = sceneBounds(state.document.root());
  const glm::dvec3 grow = b.size() * 0.1;
  b.min -= grow;
  b.max += grow;
  const int axis = std::clamp(state.section.axis, 0, 2);
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double at = frame.sectionOffset * frame.sectionNormal[axis];
  glm::dvec3 c[4];
  for (int i = 0; i < 4; ++i) {
    c[i][axis] = at;
    c[i][u] = (i == 1 || i == 2) ? b.max[u] : b.min[u];
    c[i][v] = (i >= 2) ? b.max[v] : b.min[v];
  }
  const glm::vec4 color(0.35f, 0.75f, 1.0f, 0.7f);
  for (int i = 0; i < 4; ++i) {
    lines->push_back(lineVertex(c[i], color));
    lines->push_back(lineVertex(c[(i + 1) % 4], color));
  }
}

// Beside the cursor while a gizmo handle is dragged: how far it has moved, turned or scaled
// from where the drag began, in the field's units, and the snap when it is on.
// `intoSize`: a scale that went into the part's size (scaleIntoSize), its scale field unchanged.
// Beside the cursor, moved off `taken` (the labels drawn last frame, view pixels; it sat on a
// measurement's label: an artist's test) within the view `rect`.
void drawDragReadout(const EditorState& state, const Gizmo& gizmo, const Transform& now,
                     glm::dvec2 cursor, const ViewRect& rect, const std::vector<ScreenBox>& taken,
                     bool intoSize = false) {
  const int k = gizmo.activeAxis();
  if (k < 0) return;
  const char* axis = k == 0 ? "x" : k == 1 ? "y" : "z";
  const Transform& from = gizmo.startTransform();
  char text[128];
  switch (gizmo.mode) {
    case GizmoMode::Move:
      std::snprintf(text, sizeof(text), "move %s %+.4g %s%s", axis,
                    now.translate[k] - from.translate[k],
                    unitSymbol(state.document.scene().settings.unit),
                    state.snap.enabled ? "  (snap on)" : "");
      break;
    case GizmoMode::Rotate:
      std::snprintf(text, sizeof(text), "turn %s %+.1f\u00B0 (now %.1f\u00B0)%s", axis,
                    std::remainder(now.rotateDegrees[k] - from.rotateDegrees[k], 360.0),
                    now.rotateDegrees[k], state.snap.enabled ? "  (snap 15\u00B0)" : "");
      break;
    case GizmoMode::Scale:
      if (intoSize)
        std::snprintf(text, sizeof(text), "size %s \u00D7%.3g (its size fields)%s", axis,
                      from.scale[k] != 0.0 ? now.scale[k] / from.scale[k] : 1.0,
                      state.snap.enabled ? "  (snap 0.1)" : "");
      else
        std::snprintf(text, sizeof(text), "scale %s \u00D7%.3g (now %.4g)%s", axis,
                      from.scale[k] != 0.0 ? now.scale[k] / from.scale[k] : 1.0, now.scale[k],
                      state.snap.enabled ? "  (snap 0.1)" : "");
      break;
  }
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImVec2 size = ImGui::CalcTextSize(text);
  const glm::dvec2 corner(rect.x, rect.y);
  const glm::dvec2 wanted = cursor - corner + glm::dvec2(18.0, 14.0);
  const ScreenBox box = placedLabelBox(
      {wanted - glm::dvec2(4.0, 2.0), wanted + glm::dvec2(size.x + 4.0, size.y + 2.0)}, taken,
      {0.0, 0.0}, {rect.width, rect.height}, ImGui::GetTextLineHeight() * 0.5);
  const ImVec2 at(float(corner.x + box.lo.x + 4.0), float(corner.y + box.lo.y + 2.0));
  draw->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + size.x + 4, at.y + size.y + 2),
                      IM_COL32(20, 22, 26, 210), 3.0f);
  draw->AddText(at, IM_COL32(240, 240, 240, 255), text);
}

}  // namespace

double Viewport::sceneRadius(const EditorState& state) const {
  Bounds b = sceneBounds(state.document.root());
  if (b.empty()) return std::max(camera.distance, 1.0);
  const double radius =
      std::max(glm::length(b.size()) * 0.5 + glm::length(b.center() - camera.target), 1e-6);
  // Up to the next quarter power of two: the clip planes (and so the view) stay put while a part
  // moves a little. They followed the scene's bounds exactly, so a gizmo drag changed the view
  // it is worked out in, frame after frame with the mouse at rest (a new transform from rounding
  // alone every frame: a new evaluation and, after an undo in the drag, a new undo step each), and
  // every frame of a drag was drawn as a moved view (the coarse image) rather than a new result.
  return std::exp2(std::ceil(std::log2(radius) * 4.0) / 4.0);
}

ScreenMapping Viewport::mapping(const EditorState& state, const ViewRect& rect) const {
  ScreenMapping m;
  double aspect = rect.width / std::max(rect.height, 1.0);
  m.viewProjection = camera.projection(aspect, sceneRadius(state)) * camera.view();
  m.size = glm::dvec2(rect.width, rect.height);
  m.eye = camera.ortho ? camera.target - camera.forward() * camera.distance * 4.0 : camera.eye();
  m.forward = camera.forward();
  m.ortho = camera.ortho;
  m.unitsPerPixel = camera.ortho ? camera.unitsPerPixel(rect.height)
                                 : camera.unitsPerPixel(rect.height) / camera.distance;
  return m;
}

bool Viewport::gizmoPlacement(const EditorState& state, glm::dmat4* parentWorld,
                              Transform* transform, bool* pivot) {
  if (gizmo_.dragging() && pivotGroup_) {  // the pivot as the drag has moved it
    *parentWorld = glm::dmat4(1.0);
    *transform = pivotNow_;
    *pivot = true;
    return true;
  }
  // The active part, or the selected group holding it (the part moves with it).
  const NodeId active = primarySelection(state);
  const NodeId id = active ? selectedHolder(state.document.root(), state.selection, active) : 0;
  const NodePtr node = id ? findNode(state.document.root(), id) : nullptr;
  if (!node) return false;
  // An instance shows its target where the target's own transform puts it, its own origin
  // elsewhere (the parent's, for a new one: an artist found its gizmo at the world's origin):
  // its gizmo sits on what it shows, moving it as a group's pivot does.
  *pivot = !gizmo_.dragging() &&
           ((state.pivotAtSelectionCentre &&
             independentSelectionCount(state.document.root(), state.selection) >= 2) ||
            node->kind == NodeKind::Instance);
  if (*pivot) {
    const Bounds& b = cachedSelectionBounds(state);
    if (b.empty()) {
      *pivot = false;
    } else {
      *parentWorld = glm::dmat4(1.0);
      *transform = Transform();
      transform->translate = b.center();
      return true;
    }
  }
  *parentWorld = parentWorldMatrix(state.document.root(), id);
  *transform = node->transform;
  return true;
}

bool Viewport::placeGizmo(const EditorState& state) {
  glm::dmat4 parentWorld;
  Transform transform;
  bool pivot = false;
  if (!gizmoPlacement(state, &parentWorld, &transform, &pivot)) return false;
  gizmo_.mode = state.gizmoMode;
  gizmo_.place(parentWorld, transform);
  return true;
}

void Viewport::viewAll(const EditorState& state) {
  Bounds b = sceneBounds(state.document.root());
  if (b.empty()) {
    // The view spans emptySceneSpan units (the camera's field shows about 0.8 of its distance).
    camera.target = glm::dvec3(0.0);
    camera.distance = 1.25 * emptySceneSpan(state.document.scene().settings.unit);
    pendingFrame_.reset();
    return;
  }
  pendingFrame_ = b;
}

void Viewport::keepCameraOutside(EditorState& state) {
  if (state.document.interacting() || gizmo_.dragging()) return;  // judged when it ends
  const uint64_t revision = state.document.revision();
  if (state.requestViewAll) {  // a new or opened document: framed this frame anyway
    cameraCheckedRevision_ = revision;
    cameraWasInside_ = false;
    return;
  }
  const Bounds b = sceneBounds(state.document.root());
  const glm::dvec3 eye = camera.eye();
  const bool inside = !b.empty() && eye.x > b.min.x && eye.y > b.min.y && eye.z > b.min.z &&
                      eye.x < b.max.x && eye.y < b.max.y && eye.z < b.max.z;
  if (revision != cameraCheckedRevision_ && cameraCheckedRevision_ != ~uint64_t(0) && inside &&
      !cameraWasInside_) {
    viewAll(state);
    logInfo(state, "the result grew around the camera: the view now frames the whole scene");
    cameraWasInside_ = false;  // framed this frame
  } else {
    cameraWasInside_ = inside;
  }
  cameraCheckedRevision_ = revision;
}

void Viewport::frameSelected(const EditorState& state) {
  Bounds b = selectionBounds(state.document.root(), state.selection);
  if (b.empty())
    viewAll(state);
  else
    pendingFrame_ = b;
}

bool Viewport::revealSelection(EditorState& state, const ViewRect& rect) {
  state.revealSelection = false;
  const Bounds part = selectionBounds(state.document.root(), state.selection);
  if (part.empty() || pendingFrame_) return false;  // a framing already asked shows it
  const ScreenMapping view = mapping(state, rect);
  bool shown = true;
  for (int i = 0; i < 8 && shown; ++i) {
    const glm::dvec3 corner(i & 1 ? part.max.x : part.min.x, i & 2 ? part.max.y : part.min.y,
                            i & 4 ? part.max.z : part.min.z);
    glm::dvec2 pixel;
    shown = view.toScreen(corner, &pixel) && pixel.x >= 0.0 && pixel.y >= 0.0 &&
            pixel.x <= view.size.x && pixel.y <= view.size.y;
  }
  if (shown) return false;
  // What the view showed: the rectangle through its target, across the screen.
  const double halfHeight = 0.5 * camera.unitsPerPixel(rect.height) * rect.height;
  const double halfWidth = halfHeight * rect.width / std::max(rect.height, 1.0);
  Bounds both = part;
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      both.include(camera.target + camera.right() * (sx * halfWidth) +
                   camera.up() * (sy * halfHeight));
  camera.frame(both, rect.width / std::max(rect.height, 1.0));
  const NodePtr first = findNode(state.document.root(), state.selection.front());
  logInfo(state, (state.selection.size() == 1 && first ? nodeLabel(*first) + " was"
                                                       : std::string("the new parts were")) +
                     " out of view: the view moved out to show " +
                     (state.selection.size() == 1 ? "it" : "them") +
                     " beside what it showed (Home shows the whole scene)");
  return true;
}

void Viewport::toggleOrtho(const EditorState& state) {
  pendingOrthoToggle_ = sceneBounds(state.document.root());
}

void Viewport::framePending(const ViewRect& rect, const EditorState& state) {
  const double aspect = rect.width / std::max(rect.height, 1.0);
  // A view that changed shape keeps the whole scene in view where it showed it whole.
  if (rect.width > 0.0 && rect.height > 0.0) {
    if (lastAspect_ > 0.0 && aspect != lastAspect_ && !pendingFrame_)
      reshape_.apply(camera, sceneBounds(state.document.root()), lastAspect_, aspect);
    lastAspect_ = aspect;
  }
  if (pendingOrthoToggle_) camera.setOrtho(!camera.ortho, *pendingOrthoToggle_, aspect);
  pendingOrthoToggle_.reset();
  if (!pendingFrame_) return;
  camera.frame(*pendingFrame_, aspect);
  pendingFrame_.reset();
}

// Framing, axis views, projection and gizmo modes from the keyboard (when ImGui does not want it).
void Viewport::handleKeys(EditorState& state) {
  auto pressed = [&](int key, int keypad, int mods) {
    return keyPressed(state, key, mods) || keyPressed(state, keypad, mods);
  };
  const int ctrl = GLFW_MOD_CONTROL;
  if (keyPressed(state, GLFW_KEY_F)) frameSelected(state);
  if (keyPressed(state, GLFW_KEY_HOME)) viewAll(state);
  if (pressed(GLFW_KEY_1, GLFW_KEY_KP_1, 0)) camera.setAxisView(AxisView::Front);
  if (pressed(GLFW_KEY_1, GLFW_KEY_KP_1, ctrl)) camera.setAxisView(AxisView::Back);
  if (pressed(GLFW_KEY_3, GLFW_KEY_KP_3, 0)) camera.setAxisView(AxisView::Right);
  if (pressed(GLFW_KEY_3, GLFW_KEY_KP_3, ctrl)) camera.setAxisView(AxisView::Left);
  if (pressed(GLFW_KEY_7, GLFW_KEY_KP_7, 0)) camera.setAxisView(AxisView::Top);
  if (pressed(GLFW_KEY_7, GLFW_KEY_KP_7, ctrl)) camera.setAxisView(AxisView::Bottom);
  if (pressed(GLFW_KEY_5, GLFW_KEY_KP_5, 0)) toggleOrtho(state);
  // Not during a drag: a scale left half way as a move kept its resized parts (a review).
  if (!gizmo_.dragging()) {
    if (keyPressed(state, GLFW_KEY_W)) state.gizmoMode = GizmoMode::Move;
    if (keyPressed(state, GLFW_KEY_E)) state.gizmoMode = GizmoMode::Rotate;
    if (keyPressed(state, GLFW_KEY_R)) state.gizmoMode = GizmoMode::Scale;
  }
}

void Viewport::handleInput(EditorState& state, const ViewRect& rect) {
  framePending(rect, state);
  if (state.revealSelection) revealSelection(state, rect);
  ImGuiIO& io = ImGui::GetIO();
  const glm::dvec2 mouse(io.MousePos.x - rect.x, io.MousePos.y - rect.y);
  const bool inside = mouse.x >= 0 && mouse.y >= 0 && mouse.x < rect.width && mouse.y < rect.height;
  const ScreenMapping view = mapping(state, rect);

  if (!io.WantCaptureKeyboard && !io.WantTextInput) handleKeys(state);
  // What new parts and the snap are sized from.
  state.viewExtent = camera.unitsPerPixel(rect.height) * rect.height;
  if (state.snapFollowsGrid)
    state.snap.step = groundGridStep(sceneBounds(state.document.root()),
                                     emptySceneSpan(state.document.scene().settings.unit));

  // An ongoing gizmo drag keeps the mouse wherever it goes.
  if (gizmo_.dragging()) {
    if (state.cancelGizmoDrag) {  // Escape: everything the drag moved goes back, no undo step
      state.cancelGizmoDrag = false;
      gizmo_.end();
      state.document.cancelInteraction();
      dragGesture_ = ResizeGesture();
      dragFitted_.clear();
      return;
    }
    if (io.MouseDown[0] && placeGizmo(state)) {
      Transform t = gizmo_.drag(view, mouse, state.snap);
      const Transform dragged = t;  // as the gizmo moved it, for the readout
      bool intoSize = false;
      std::vector<NodeId> sheared;  // parts the drag's motion would shear
      if (pivotGroup_) {
        // The pivot's motion, applied to every selected part from where the drag began.
        pivotNow_ = t;
        const glm::dmat4 motion = t.matrix() * glm::inverse(gizmo_.startTransform().matrix());
        guarded(state, [&] {
          for (const auto& [id, transform] :
               movedSelection(dragStart_, state.selection, motion, &sheared))
            state.document.setTransform(id, transform);
        });
      } else {
        const NodeId id =
            selectedHolder(state.document.root(), state.selection, primarySelection(state));
        guarded(state, [&] {
          state.document.setTransform(id, t);
          // Scaled about its origin (a box's middle), a part resting on the ground or on
          // another part sank into it or floated off it: kept on it from where the drag began,
          // as a scale or size typed in the inspector (an artist's test).
          if (state.gizmoMode == GizmoMode::Scale) {
            // One primitive scaled changes its size instead, where its parameters hold it (a
            // rounded box's corners turned oval, and its size field kept the old size: an
            // artist's test).
            const NodePtr start = findNode(dragStart_, id);
            PrimitiveParams sized;
            if (start && independentSelectionCount(dragStart_, state.selection) == 1 &&
                scaleIntoSize(*start, &t, &sized, &dragFitted_)) {
              state.document.setTransform(id, t);
              state.document.setParams(id, sized);
              intoSize = true;
            } else {
              dragFitted_.clear();
              if (start && isPrimitive(start->kind))
                state.document.setParams(id, start->params);  // as the drag began
            }
            // Kept where it rested, and what rests on it and what cuts through or into it
            // follow, from where the drag began (followResize).
            const ResizeStep step = followResize(state.document, dragGesture_, id, state.selection);
            const Rest& rest = step.rest;
            t = findNode(state.document.root(), id)->transform;
            if (rest.moved && !restSaid_) {
              restSaid_ = true;
              const NodePtr part = findNode(dragStart_, id);
              const NodePtr on = rest.on ? findNode(dragStart_, rest.on) : nullptr;
              logInfo(state, quotedName(*part) + " rested on " +
                                 (on ? quotedName(*on) : "the ground") +
                                 " and stays on it as it is scaled" +
                                 (on ? " (it grows from its base)" : ""));
            }
            dragResized_ = id;
          }
          for (const auto& [follower, transform] :
               followingTransforms(dragStart_, state.selection, id, t, &sheared))
            state.document.setTransform(follower, transform);
        });
      }
      // Said once a drag: a turned part cannot follow a stretch along another axis.
      if (!sheared.empty() && !shearSaid_) {
        shearSaid_ = true;
        const NodePtr part = findNode(dragStart_, sheared.front());
        logWarning(state,
                   "\"" + (part ? part->name : std::string("a part")) +
                       "\" is turned: a stretch along the view's axes would shear it, which a "
                       "part's move, turn and scale cannot hold; it gets the nearest move, turn "
                       "and scale (its turn may change too). Scale it alone, along its own axes, "
                       "for an exact stretch");
      }
      drawDragReadout(state, gizmo_, pivotGroup_ ? t : dragged,
                      glm::dvec2(io.MousePos.x, io.MousePos.y), rect, labelBoxes_, intoSize);
    } else {
      gizmo_.end();
      state.document.endInteraction();
      // What followed a part scaled, as the drag left it (said once, at its end), then a
      // relation its size fitted (a corner radius made smaller): last, so that the status bar
      // shows it (as the inspector says it).
      if (const auto it = dragGesture_.following.find(dragResized_);
          it != dragGesture_.following.end())
        for (const FollowMessage& m :
             resizeFollowingMessages(state.document.root(), dragResized_, it->second))
          (m.warning ? logWarning : logInfo)(state, m.text);
      if (!dragFitted_.empty())
        if (const NodePtr part = findNode(state.document.root(), dragResized_))
          logInfo(state, fittedParamsMessage(*part, dragFitted_, "size",
                                             unitSymbol(state.document.scene().settings.unit)));
      dragFitted_.clear();
      dragGesture_ = ResizeGesture();
    }
    return;
  }
  if (navigating_) {
    if (!io.MouseDown[2] && !io.MouseDown[0]) navigating_ = false;
  }
  // A palette item released over the view (not over a panel): placed there. While it is dragged
  // there, the part under the pointer is looked up (at most every kDropHoverSeconds: a pick
  // draws the splats) for the drag's tooltip.
  const ImGuiPayload* payload = ImGui::GetDragDropPayload();
  const bool paletteOverView = payload && payload->IsDataType(kPalettePayload) && inside &&
                               !ImGui::IsWindowHovered(ImGuiHoveredFlags_AnyWindow);
  if (paletteOverView && ImGui::IsMouseReleased(0)) {
    int item = 0;
    std::memcpy(&item, payload->Data, sizeof(item));
    drop_ = PendingDrop{mouse, item, dropMode(state, heldDropModifiers())};
  }
  if (paletteOverView && !drop_) {
    if (dropHoverClock_.seconds() >= kDropHoverSeconds) dropHover_ = mouse;
  } else {
    dropHover_.reset();
    state.paletteDropPart = 0;
  }
  // A box selection keeps the mouse until released, over panels too.
  if (boxFrom_) {
    const ImVec2 a(float(rect.x + boxFrom_->x), float(rect.y + boxFrom_->y));
    const ImVec2 b(float(rect.x + mouse.x), float(rect.y + mouse.y));
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    draw->AddRectFilled(ImVec2(std::min(a.x, b.x), std::min(a.y, b.y)),
                        ImVec2(std::max(a.x, b.x), std::max(a.y, b.y)), IM_COL32(255, 150, 40, 36));
    draw->AddRect(ImVec2(std::min(a.x, b.x), std::min(a.y, b.y)),
                  ImVec2(std::max(a.x, b.x), std::max(a.y, b.y)), IM_COL32(255, 150, 40, 200));
    if (!io.MouseDown[0]) {
      box_ = PendingBox{*boxFrom_, mouse, io.KeyCtrl || io.KeyShift};
      boxFrom_.reset();
    }
    return;
  }
  if (io.WantCaptureMouse && !navigating_) {
    hot_ = -1;
    clickPending_ = false;
    return;
  }

  // The measure tool takes clicks on parts; the gizmo is not offered meanwhile.
  const bool haveGizmo = !state.measure.active && placeGizmo(state);
  hot_ = haveGizmo && inside && !navigating_ ? gizmo_.hover(view, mouse) : -1;

  if (inside && io.MouseWheel != 0.0f)
    wheel_ = PendingWheel{mouse, (wheel_ ? wheel_->steps : 0.0) + io.MouseWheel};

  const bool middle = io.MouseDown[2];
  const bool altLeft = io.MouseDown[0] && io.KeyAlt;
  if ((ImGui::IsMouseClicked(2) || (ImGui::IsMouseClicked(0) && io.KeyAlt)) && inside)
    navigating_ = true;
  if (navigating_ && (middle || altLeft)) {
    glm::dvec2 d(io.MouseDelta.x, io.MouseDelta.y);
    if (io.KeyShift)
      camera.pan(d.x, d.y, rect.height);
    else
      camera.orbit(d.x, d.y);
    return;
  }

  if (ImGui::IsMouseClicked(0) && inside && !io.KeyAlt) {
    if (hot_ >= 0) {
      state.document.beginInteraction();
      glm::dmat4 parentWorld;
      Transform transform;
      gizmoPlacement(state, &parentWorld, &transform, &pivotGroup_);
      pivotNow_ = transform;
      gizmo_.begin(hot_, view, mouse);
      dragStart_ = state.document.root();
      shearSaid_ = false;
      restSaid_ = false;
      dragGesture_ = ResizeGesture();
      dragGesture_.begin(dragStart_, state.document.interactionsBegun());
      dragFitted_.clear();
      return;
    }
    clickPending_ = true;
  }
  if (clickPending_ && ImGui::IsMouseDragging(0, 4.0f) && !state.measure.active) {
    clickPending_ = false;
    const ImVec2 delta = ImGui::GetMouseDragDelta(0, 0.0f);
    boxFrom_ = mouse - glm::dvec2(delta.x, delta.y);
  }
  if (clickPending_ && ImGui::IsMouseReleased(0)) {
    clickPending_ = false;
    click_ = PendingClick{mouse, io.KeyCtrl || io.KeyShift};
  }
  // A right click: the part's menu (it did nothing; only the outliner's rows had one).
  if (ImGui::IsMouseClicked(1) && inside && !state.measure.active)
    contextClick_ = PendingClick{mouse, false};
}

void viewPixels(const ViewRect& rect, int framebufferHeight, double pixelScale, int* x, int* y,
                int* width, int* height) {
  *x = int(std::lround(rect.x * pixelScale));
  *width = std::max(1, int(std::lround(rect.width * pixelScale)));
  *height = std::max(1, int(std::lround(rect.height * pixelScale)));
  *y = framebufferHeight - int(std::lround((rect.y + rect.height) * pixelScale));
}

ViewportFrame Viewport::makeFrame(const EditorState& state, const ViewRect& rect,
                                  int framebufferHeight, double pixelScale) const {
  ViewportFrame frame;
  const ScreenMapping view = mapping(state, rect);
  frame.viewProjection = view.viewProjection;
  frame.eye = view.eye;
  frame.forward = camera.forward();
  frame.up = camera.up();
  frame.ortho = camera.ortho;
  viewPixels(rect, framebufferHeight, pixelScale, &frame.x, &frame.y, &frame.width, &frame.height);
  frame.sectionOn = sectionPlane(state, &frame.sectionNormal, &frame.sectionOffset);
  return frame;
}

std::optional<PickHit> Viewport::pickAt(ViewportRenderer& renderer, const EditorState& state,
                                        const ViewRect& rect, glm::dvec2 mouse, double pixelScale) {
  framePending(rect, state);
  const ViewportFrame frame = makeFrame(state, rect, 0, pixelScale);
  const int px = int(std::floor(mouse.x * pixelScale));
  const int py = frame.height - 1 - int(std::floor(mouse.y * pixelScale));
  return renderer.pick(frame, px, py);
}

Placement Viewport::placementAt(ViewportRenderer& renderer, const EditorState& state,
                                const ViewRect& rect, glm::dvec2 mouse, double pixelScale) {
  // On the surface under the cursor; else on the ground plane where the ray meets it; else
  // (looking at or above the horizon) on the ground below the point the camera orbits.
  Placement placement;
  if (std::optional<PickHit> hit = pickAt(renderer, state, rect, mouse, pixelScale)) {
    placement.point = hit->position;
    placement.normal = hit->normal;
    if (hit->normal) {
      const FaceSnap snap =
          snappedToBoxFace(state.document.root(), hit->leaf, hit->position, *hit->normal);
      placement.point = snap.point;
      placement.normal = snap.normal;
    }
    placement.part = dropTargetFor(state.document.root(), hit->leaf);
    return placement;
  }
  const Ray ray = camera.rayThrough(mouse, glm::dvec2(rect.width, rect.height));
  placement.onGround = true;
  placement.point = camera.target;
  if (std::fabs(ray.direction.z) > 1e-9) {
    const double t = -ray.origin.z / ray.direction.z;
    if (t > 0.0) placement.point = ray.origin + t * ray.direction;
  }
  placement.point.z = 0.0;
  return placement;
}

void Viewport::resolvePicks(ViewportRenderer& renderer, EditorState& state, const ViewRect& rect,
                            double pixelScale) {
  if (wheel_) {
    const bool samePivot =
        wheelPivot_ && glm::length(wheelPivot_->mouse - wheel_->mouse) < 1.0 &&
        wheelPivot_->target == camera.target && wheelPivot_->distance == camera.distance &&
        wheelPivot_->yaw == camera.yawDegrees && wheelPivot_->pitch == camera.pitchDegrees &&
        wheelPivot_->ortho == camera.ortho;
    if (!samePivot) {
      wheelPivot_ = WheelPivot{wheel_->mouse, std::nullopt};
      if (std::optional<PickHit> hit = pickAt(renderer, state, rect, wheel_->mouse, pixelScale)) {
        wheelPivot_->point = hit->position;
      } else {
        // Over empty space: towards the point under the cursor at the target's depth, not the
        // target (zoomed in from the sky the view went into the middle of the part: an artist's
        // test).
        const Ray ray = camera.rayThrough(wheel_->mouse, glm::dvec2(rect.width, rect.height));
        const double along = glm::dot(ray.direction, camera.forward());
        if (along > 1e-9)
          wheelPivot_->point =
              ray.origin +
              ray.direction * (glm::dot(camera.target - ray.origin, camera.forward()) / along);
      }
    }
    if (wheelPivot_->point)
      camera.zoomAbout(*wheelPivot_->point, wheel_->steps);
    else
      camera.zoom(wheel_->steps);
    wheelPivot_->target = camera.target;
    wheelPivot_->distance = camera.distance;
    wheelPivot_->yaw = camera.yawDegrees;
    wheelPivot_->pitch = camera.pitchDegrees;
    wheelPivot_->ortho = camera.ortho;
    wheel_.reset();
  }
  if (click_ && state.measure.active) {
    std::optional<PickHit> hit = pickAt(renderer, state, rect, click_->mouse, pixelScale);
    if (hit) {
      // What the view shows around the click, read once: a snap point counts where the view
      // shows a surface point within two cells (and two pixels) of it, at its pixel or one next
      // to it (a corner on the silhouette), and where it lies on the surface clicked, near the
      // hit (not a floor's edge far below a rim on the same line of sight).
      const ScreenMapping view = mapping(state, rect);
      const ViewportFrame frame = makeFrame(state, rect, 0, pixelScale);
      const auto toFrame = [&](glm::dvec2 mouse) {
        return glm::ivec2(int(std::floor(mouse.x * pixelScale)),
                          frame.height - 1 - int(std::floor(mouse.y * pixelScale)));
      };
      const glm::ivec2 at = toFrame(click_->mouse);
      const ViewportRenderer::PickWindow around = renderer.shownAround(
          frame, at.x, at.y, int(std::ceil((kMeasureSnapPixels + 2.0) * pixelScale)));
      const double cell = state.preview ? state.preview->stats.grid.h : 0.0;
      const auto pixelSize = [&](const glm::dvec3& world) {
        return view.unitsPerPixel *
               (view.ortho ? 1.0 : std::max(glm::dot(world - view.eye, view.forward), 1e-9));
      };
      const double reach = 3.0 * kMeasureSnapPixels * pixelSize(hit->position) + 2.0 * cell;
      const auto shown = [&](const glm::dvec3& world) {
        glm::dvec2 pixel;
        if (glm::length(world - hit->position) > reach || !view.toScreen(world, &pixel))
          return false;
        const double tolerance = 2.0 * cell + 2.0 * pixelSize(world);
        const glm::ivec2 p = toFrame(pixel);
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            if (const std::optional<glm::dvec3> q = around.pointAt(p.x + dx, p.y + dy))
              if (glm::length(*q - world) <= tolerance) return true;
        return false;
      };
      std::string what;
      const std::optional<glm::dvec3> capEdge =
          hit->cap ? around.capEdgeNear(at.x, at.y, kMeasureSnapPixels * pixelScale) : std::nullopt;
      const glm::dvec3 p =
          snapMeasurePoint(state, view, *hit, click_->mouse, shown, &what, capEdge);
      measureClick(state, hit->leaf, p);
      state.measure.lastSnap = what;
    } else {
      logInfo(state, "measure: click on a part (or the section's cap); Esc leaves the tool");
    }
    click_.reset();
  }
  if (click_) {
    std::optional<PickHit> hit = pickAt(renderer, state, rect, click_->mouse, pixelScale);
    if (hit && findNode(state.document.root(), hit->leaf)) {
      selectNode(state, hit->leaf, click_->extend);
      state.revealInOutliner = hit->leaf;  // its row opened and scrolled into view
    } else if (!click_->extend)
      clearSelection(state);
    click_.reset();
  }
  if (contextClick_) {
    // The part under the pointer, selected unless it already is (a selection of several keeps
    // them, as the outliner's menu does), its menu opened by drawModals.
    std::optional<PickHit> hit = pickAt(renderer, state, rect, contextClick_->mouse, pixelScale);
    if (hit && findNode(state.document.root(), hit->leaf)) {
      if (!isSelected(state, hit->leaf)) selectNode(state, hit->leaf);
      state.viewContextMenu = hit->leaf;
    }
    contextClick_.reset();
  }
  if (box_) {
    const ViewportFrame frame = makeFrame(state, rect, 0, pixelScale);
    auto pixel = [&](glm::dvec2 m) {
      return glm::ivec2(int(std::floor(m.x * pixelScale)),
                        frame.height - int(std::floor(m.y * pixelScale)));
    };
    const glm::ivec2 a = pixel(box_->from), b = pixel(box_->to);
    const std::vector<uint32_t> leaves = renderer.pickLeaves(frame, a.x, a.y, b.x, b.y);
    if (!box_->extend) clearSelection(state);
    for (uint32_t leaf : leaves)
      if (findNode(state.document.root(), leaf) && !isSelected(state, leaf))
        state.selection.push_back(leaf);
    box_.reset();
  }
  if (dropHover_) {
    const std::optional<PickHit> hit = pickAt(renderer, state, rect, *dropHover_, pixelScale);
    state.paletteDropPart = hit ? dropTargetFor(state.document.root(), hit->leaf) : 0;
    dropHover_.reset();
    dropHoverClock_ = Stopwatch();
  }
  if (drop_) {
    state.paletteDropPart = 0;
    const Placement placement = placementAt(renderer, state, rect, drop_->mouse, pixelScale);
    if (drop_->item == kImportMeshItem) {
      state.importPlacement = placement;
      state.dialog.open(DialogPurpose::ImportMesh, importFolder(state));
    } else {
      const PlaceMode saved = state.placeMode;
      state.placeMode = drop_->mode;
      addPrimitiveAt(state, NodeKind(drop_->item), placement);
      state.placeMode = saved;
    }
    drop_.reset();
  }
}

void Viewport::drawAnnotations(const EditorState& state, const ViewRect& rect) {
  if (guidesRevision_ != state.document.revision() || guidesOf_ != state.selection) {
    guidesRevision_ = state.document.revision();
    guidesOf_ = state.selection;
    guides_ = patternGuides(state);
  }
  // The labels keep off the gizmo's handles (one covered a handle: an artist's test) and off
  // one another; the gizmo drag's readout (drawn next frame) off the labels.
  std::vector<ScreenBox> gizmoBox;
  glm::dmat4 parentWorld;
  Transform transform;
  bool pivot = false;
  if (!state.selection.empty() && !state.measure.active &&
      gizmoPlacement(state, &parentWorld, &transform, &pivot)) {
    Gizmo gizmo = gizmo_;
    gizmo.mode = state.gizmoMode;
    gizmo.place(parentWorld, transform);
    ScreenBox box;
    if (gizmo.screenBox(mapping(state, rect), &box)) gizmoBox.push_back(box);
  }
  const size_t gizmoBoxes = gizmoBox.size();
  drawPatternGuides(guides_, mapping(state, rect), rect.x, rect.y, &gizmoBox);
  labelBoxes_ = drawMeasureLabels(state, mapping(state, rect), rect.x, rect.y, gizmoBox);
  // The readout stays beside the cursor, on the gizmo: off the labels only.
  labelBoxes_.erase(labelBoxes_.begin(), labelBoxes_.begin() + long(gizmoBoxes));
}

bool sectionPlane(const EditorState& state, glm::dvec3* normal, double* offset) {
  if (!state.section.on) return false;
  const Bounds b = sceneBounds(state.document.root());
  if (b.empty()) return false;
  const int axis = std::clamp(state.section.axis, 0, 2);
  const double at = sectionAt(state.section, b);
  *normal = glm::dvec3(0.0);
  (*normal)[axis] = state.section.flip ? -1.0 : 1.0;
  *offset = state.section.flip ? -at : at;
  return true;
}

double sectionAt(const SectionState& section, const Bounds& scene) {
  if (section.at) return *section.at;
  const int axis = std::clamp(section.axis, 0, 2);
  return scene.min[axis] +
         std::clamp(section.startFraction, 0.0, 1.0) * (scene.max[axis] - scene.min[axis]);
}

void placeSection(EditorState& state) {
  if (!state.section.on || state.section.at) return;
  const Bounds b = sceneBounds(state.document.root());
  if (!b.empty()) state.section.at = sectionAt(state.section, b);
}

const Bounds& Viewport::cachedSelectionBounds(const EditorState& state) {
  if (selectionBoundsRevision_ != state.document.revision() ||
      selectionBoundsOf_ != state.selection) {
    selectionBoundsRevision_ = state.document.revision();
    selectionBoundsOf_ = state.selection;
    selectionBounds_ = selectionBounds(state.document.root(), state.selection);
  }
  return selectionBounds_;
}

void Viewport::draw(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
                    int framebufferHeight, double pixelScale, double lastFrameMs) {
  prepare(renderer, state, rect, framebufferHeight, pixelScale);
  drawPrepared(renderer, lastFrameMs);
}

void Viewport::drawPrepared(ViewportRenderer& renderer, double lastFrameMs) {
  const Prepared& p = prepared_;
  if (lastFrameMs >= 0.0)
    renderer.drawCached(p.frame, p.lines, p.overlay, p.triangles, lastFrameMs);
  else
    renderer.draw(p.frame, p.lines, p.overlay, p.triangles);
}

void Viewport::repaintPrepared(ViewportRenderer& renderer, const PixelRect& clip) const {
  renderer.repaintWindow(prepared_.frame, prepared_.overlay, prepared_.triangles, clip);
}

bool Viewport::prepare(ViewportRenderer& renderer, const EditorState& state, const ViewRect& rect,
                       int framebufferHeight, double pixelScale) {
  framePending(rect, state);
  const ViewportFrame frame = makeFrame(state, rect, framebufferHeight, pixelScale);
  const ScreenMapping view = mapping(state, rect);

  std::vector<LineVertex> grid, lines, overlay, triangles;
  if (state.showGrid)
    appendGrid(sceneBounds(state.document.root()),
               emptySceneSpan(state.document.scene().settings.unit), &grid);
  renderer.setBackdrop(std::move(grid));
  if (frame.sectionOn) appendSectionOutline(state, frame, &lines);
  if (!state.selection.empty()) {
    const Bounds& b = cachedSelectionBounds(state);
    if (!b.empty()) appendBox(b, glm::vec4(1.0f, 0.62f, 0.2f, 0.55f), &overlay);
  }
  appendMeasureLines(state, view, &overlay);
  Gizmo gizmo = gizmo_;
  glm::dmat4 parentWorld;
  Transform transform;
  bool pivot = false;
  if (!state.selection.empty() && !state.measure.active &&
      gizmoPlacement(state, &parentWorld, &transform, &pivot)) {
    gizmo.mode = state.gizmoMode;
    gizmo.place(parentWorld, transform);
    gizmo.appendGeometry(view, hot_, &overlay, &triangles);
  }
  const bool shown = renderer.windowShows(frame, lines, overlay, triangles);
  prepared_ = Prepared{frame, std::move(lines), std::move(overlay), std::move(triangles)};
  return shown;
}

}  // namespace strata::ui
