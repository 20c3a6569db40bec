// The viewport's orbit camera: it looks at `target` from `distance` away, z up. Plain math, no
// GL. Angles in degrees, lengths in scene units, pixels with y down from the top-left.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "engine/geometry/mesh.h"

namespace strata::ui {

// Fixed views (numpad style: 1 front, 3 right, 7 top; Ctrl for the opposite side).
enum class AxisView { Front, Back, Right, Left, Top, Bottom };

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit
};

class Camera {
 public:
  glm::dvec3 target{0.0};
  double distance = 10.0;
  double yawDegrees = -60.0;   // of the eye around z, from +x
  double pitchDegrees = 25.0;  // of the eye above the xy plane, [-90, 90]
  double fovYDegrees = 35.0;   // perspective vertical field of view
  bool ortho = false;

  glm::dvec3 eye() const { return target + toEye() * distance; }
  glm::dvec3 toEye() const;  // unit, from the target towards the eye
  glm::dvec3 forward() const { return -toEye(); }
  glm::dvec3 up() const;     // unit, screen up
  glm::dvec3 right() const;  // unit, screen right

  glm::dmat4 view() const;
  // `sceneRadius` keeps the far plane behind the whole scene.
  glm::dmat4 projection(double aspect, double sceneRadius) const;
  // Scene units per pixel at the target's depth, for a viewport `heightPixels` high.
  double unitsPerPixel(double heightPixels) const;

  void orbit(double dxPixels, double dyPixels);
  void pan(double dxPixels, double dyPixels, double heightPixels);
  // Zooms about the target: the distance shrinks by 0.85 per step (grows for negative steps).
  void zoom(double wheelSteps);
  // Zooms about `point` (a surface point under the cursor): the eye, the target and the distance
  // scale about it by 0.85 per step, so the point stays under the same pixel and the eye moves
  // along its line of sight to the point, closing in on it without reaching it. Zooming about
  // the target alone passed through the surface in front of it when the target lay inside a
  // part (an artist's test).
  void zoomAbout(const glm::dvec3& point, double wheelSteps);
  // Looks at `bounds` from the current direction, as close as the box's corners allow with a
  // small margin, in a view of width / height `aspect`.
  void frame(const Bounds& bounds, double aspect);
  // The distance from `target` (unchanged) at which `bounds` is in view with frame()'s margin, in
  // this projection and a view of width / height `aspect`.
  double distanceToShow(const Bounds& bounds, double aspect) const;
  // Whether every corner of `bounds` is in view.
  bool shows(const Bounds& bounds, double aspect) const;
  // Orthographic (true) or perspective. Where the whole of `scene` was in view it stays in view:
  // the distance grows as the new projection needs (an orthographic view framed close shows the
  // parts in front of the target larger once in perspective), never shrinks.
  void setOrtho(bool on, const Bounds& scene, double aspect);
  // The view changed shape from width / height `aspectBefore` to `aspectNow` (the window
  // resized, a panel's splitter dragged). Where the whole of `scene` was in view and no longer
  // would be, the camera moves back along its line of sight (target and direction kept) until it
  // is; otherwise nothing changes (a view zoomed in on a detail stays). A window made narrower
  // cut the scene it had shown whole at its sides (an artist's test).
  void reshape(const Bounds& scene, double aspectBefore, double aspectNow);
  void setAxisView(AxisView view);
  // "front", "top", ... while the camera looks exactly along an axis (setAxisView, or orbited
  // there), else "".
  const char* axisViewName() const;

  // The ray through a pixel of a viewport of `size` pixels.
  Ray rayThrough(glm::dvec2 pixel, glm::dvec2 size) const;
};

// A view changing shape over several frames (a window dragged narrower, then wider): each step
// is Camera::reshape from the shape and distance the artist left the camera at, so that the
// distance it gave up for a narrower view comes back once the view has room again (framed,
// narrowed and widened: framed as before). A camera moved between two steps starts anew.
class ViewReshape {
 public:
  void apply(Camera& camera, const Bounds& scene, double aspectBefore, double aspectNow);

 private:
  bool active_ = false;
  Camera left_;            // the camera as the last step left it
  double distance_ = 0.0;  // the distance the artist left it at
  double aspect_ = 0.0;    // and the view's shape then
};

}  // namespace strata::ui
