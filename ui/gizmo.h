// The transform gizmo: move (W), rotate (E) and scale (R) handles on the selected node, picked by
// screen-space distance, with grid and angle snapping. Plain math, no GL: it produces line and
// triangle vertices for the viewport renderer and new Transforms for the document.
//
//   move:   arrows along the parent's axes; dragging changes translate[k]
//   rotate: one ring per Euler angle, around the axis that angle turns about right now (z about
//           the parent's z, y about Rz*y, x about Rz*Ry*x), so the ring under the mouse is exactly
//           the rotation applied; dragging changes rotateDegrees[k]
//   scale:  handles along the node's own axes; dragging changes scale[k]
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

#include "engine/geometry/transform.h"
#include "ui/camera.h"
#include "ui/viewport_renderer.h"

namespace strata::ui {

enum class GizmoMode { Move, Rotate, Scale };

struct GizmoSnap {
  bool enabled = false;
  double step = 1.0;      // move: scene units; scale: factor step (e.g. 0.1)
  double degrees = 15.0;  // rotate
};

// How the view maps world points to viewport pixels (y down, origin top-left of the viewport).
struct ScreenMapping {
  glm::dmat4 viewProjection{1.0};
  glm::dvec2 size{1.0, 1.0};
  glm::dvec3 eye{0.0};
  glm::dvec3 forward{0.0, 0.0, -1.0};
  bool ortho = false;
  // Scene units per pixel: per unit of depth in perspective, absolute in orthographic.
  double unitsPerPixel = 1.0;
  // Returns false when the point is behind the camera.
  bool toScreen(const glm::dvec3& world, glm::dvec2* pixel) const;
};

// A box of screen pixels (y down, doubles): [lo, hi).
struct ScreenBox {
  glm::dvec2 lo{0.0}, hi{0.0};
  bool overlaps(const ScreenBox& o) const {
    return lo.x < o.hi.x && o.lo.x < hi.x && lo.y < o.hi.y && o.lo.y < hi.y;
  }
};

class Gizmo {
 public:
  // Places the gizmo on a node whose parent-to-world matrix is `parentWorld`, with `transform`.
  void place(const glm::dmat4& parentWorld, const Transform& transform);
  // The handle under the mouse: 0, 1, 2 for x, y, z, or -1. A ring is picked on its front half
  // (the half nearer the viewer, drawn bright; its back half is drawn faint) before any back
  // half: a ring's back half crossed the others' front halves, and an artist aiming for the z
  // ring got the y ring. Its back half is picked where no front half is near.
  int hover(const ScreenMapping& view, glm::dvec2 mouse) const;
  void begin(int axis, const ScreenMapping& view, glm::dvec2 mouse);
  bool dragging() const { return axis_ >= 0; }
  int activeAxis() const { return axis_; }
  // The node's transform when the drag began.
  const Transform& startTransform() const { return start_; }
  // The transform for the mouse at `mouse` while dragging.
  Transform drag(const ScreenMapping& view, glm::dvec2 mouse, const GizmoSnap& snap) const;
  void end() { axis_ = -1; }

  // Appends the gizmo's lines and filled handles, highlighting `hot` (-1: none).
  void appendGeometry(const ScreenMapping& view, int hot, std::vector<LineVertex>* lines,
                      std::vector<LineVertex>* triangles) const;

  // The viewport pixels the gizmo covers: the box of its handles (or rings) on screen, a few
  // pixels of margin added; false where none of it is in front of the camera. What other
  // drawings keep clear of (a measurement's label covered a handle: an artist's test).
  bool screenBox(const ScreenMapping& view, ScreenBox* box) const;

  GizmoMode mode = GizmoMode::Move;

 private:
  glm::dvec3 handleAxis(int k) const;  // unit world direction of handle k
  double handleLength(const ScreenMapping& view) const;
  // Ring k lies in the plane of *a and *b (unit, b = axis x a): its point at angle t is
  // origin + radius (cos t a + sin t b), t turning about the axis.
  void ringBasis(int k, glm::dvec3* a, glm::dvec3* b) const;
  double ringRadius(const ScreenMapping& view) const;  // scene units
  std::vector<glm::dvec3> ring(int k, const ScreenMapping& view) const;
  // Whether the ring's segment from `p` to `q` (points of ring()) lies on its back half, away
  // from the viewer by more than a sixth of its radius (a ring facing the viewer, or nearly, has
  // none).
  bool ringBackSegment(const ScreenMapping& view, const glm::dvec3& p, const glm::dvec3& q) const;
  // While dragging a ring: how far it turned (degrees, about its axis, right-handed) from the
  // grab at startMouse_ to `mouse`; `o` is the gizmo's centre on screen. The ring follows the
  // cursor where it faces the viewer; seen nearly edge-on, moving along its tangent at the
  // point grabbed turns it by the arc moved on screen, and so does moving across it (the
  // tangent turned a quarter clockwise on screen), whichever the drag went first.
  double ringTurnDegrees(const ScreenMapping& view, glm::dvec2 o, glm::dvec2 mouse) const;

  glm::dmat4 parentWorld_{1.0};
  Transform transform_;
  glm::dvec3 origin_{0.0};
  int axis_ = -1;
  Transform start_;
  glm::dvec2 startMouse_{0.0};
  // A ring seen edge-on turns with the cursor along its line or across it, whichever the drag
  // went first (0: not yet; 1: along; 2: across), kept for the drag (ringTurnDegrees).
  mutable int edgeOnWay_ = 0;
};

}  // namespace strata::ui
