#include "ui/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace strata::ui {
namespace {
constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) {
  return degrees * kPi / 180.0;
}
}  // namespace

glm::dvec3 Camera::toEye() const {
  double y = radians(yawDegrees), p = radians(pitchDegrees);
  return {std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p)};
}

glm::dvec3 Camera::up() const {
  // d(toEye)/d(pitch): defined at the poles too, so top and bottom views need no special case.
  double y = radians(yawDegrees), p = radians(pitchDegrees);
  return {-std::sin(p) * std::cos(y), -std::sin(p) * std::sin(y), std::cos(p)};
}

glm::dvec3 Camera::right() const {
  return glm::normalize(glm::cross(forward(), up()));
}

glm::dmat4 Camera::view() const {
  return glm::lookAt(eye(), target, up());
}

glm::dmat4 Camera::projection(double aspect, double sceneRadius) const {
  double radius = std::max(sceneRadius, 1e-9);
  double farPlane = distance + 4.0 * radius + distance;
  if (ortho) {
    double halfH = distance * std::tan(radians(fovYDegrees) * 0.5);
    double halfW = halfH * aspect;
    return glm::ortho(-halfW, halfW, -halfH, halfH, -farPlane, farPlane);
  }
  double nearPlane = std::max(distance * 0.01, (distance - 2.0 * radius) * 0.5);
  nearPlane = std::max(nearPlane, 1e-6);
  return glm::perspective(radians(fovYDegrees), aspect, nearPlane, farPlane);
}

double Camera::unitsPerPixel(double heightPixels) const {
  return 2.0 * distance * std::tan(radians(fovYDegrees) * 0.5) / std::max(heightPixels, 1.0);
}

void Camera::orbit(double dxPixels, double dyPixels) {
  yawDegrees -= dxPixels * 0.4;
  pitchDegrees = std::clamp(pitchDegrees + dyPixels * 0.4, -90.0, 90.0);
  yawDegrees = std::fmod(yawDegrees, 360.0);
}

void Camera::pan(double dxPixels, double dyPixels, double heightPixels) {
  double s = unitsPerPixel(heightPixels);
  target += (-dxPixels * right() + dyPixels * up()) * s;
}

void Camera::zoom(double wheelSteps) {
  distance = std::clamp(distance * std::pow(0.85, wheelSteps), 1e-6, 1e9);
}

void Camera::zoomAbout(const glm::dvec3& point, double wheelSteps) {
  const double before = distance;
  zoom(wheelSteps);
  const double k = distance / before;  // the clamped factor
  target = point + (target - point) * k;
}

void Camera::frame(const Bounds& bounds, double aspect) {
  if (bounds.empty()) return;
  target = bounds.center();
  distance = distanceToShow(bounds, aspect);
}

double Camera::distanceToShow(const Bounds& bounds, double aspect) const {
  const double margin = 1.12;
  const double tanV = std::tan(radians(fovYDegrees) * 0.5);
  const double tanH = tanV * std::max(aspect, 1e-3);
  const glm::dvec3 r = right(), u = up(), f = forward();
  double needed = 1e-6, halfHeight = 1e-6;
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 c(i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                 i & 4 ? bounds.max.z : bounds.min.z);
    glm::dvec3 d = c - target;
    double x = std::fabs(glm::dot(d, r)) * margin, y = std::fabs(glm::dot(d, u)) * margin;
    double depth = glm::dot(d, f);  // beyond the target: positive
    // Perspective: the corner must lie inside the frustum at distance + depth from the eye.
    needed = std::max({needed, x / tanH - depth, y / tanV - depth});
    halfHeight = std::max({halfHeight, y, x / std::max(aspect, 1e-3)});
  }
  // Orthographic: the view's half height is distance * tanV.
  const double d = ortho ? halfHeight / tanV : needed;
  return std::max(d, glm::length(bounds.size()) * 0.05 + 1e-6);
}

bool Camera::shows(const Bounds& bounds, double aspect) const {
  if (bounds.empty()) return false;
  const double tanV = std::tan(radians(fovYDegrees) * 0.5);
  const double tanH = tanV * std::max(aspect, 1e-3);
  const glm::dvec3 r = right(), u = up(), f = forward();
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 c(i & 1 ? bounds.max.x : bounds.min.x, i & 2 ? bounds.max.y : bounds.min.y,
                 i & 4 ? bounds.max.z : bounds.min.z);
    const glm::dvec3 d = c - target;
    // Half the view's height and width at the corner's depth.
    const double at = ortho ? distance : distance + glm::dot(d, f);
    if (at <= 0.0) return false;
    if (std::fabs(glm::dot(d, r)) > at * tanH || std::fabs(glm::dot(d, u)) > at * tanV)
      return false;
  }
  return true;
}

void Camera::setOrtho(bool on, const Bounds& scene, double aspect) {
  if (on == ortho) return;
  const bool whole = shows(scene, aspect);
  ortho = on;
  if (whole) distance = std::max(distance, distanceToShow(scene, aspect));
}

void Camera::reshape(const Bounds& scene, double aspectBefore, double aspectNow) {
  if (aspectBefore == aspectNow || !shows(scene, aspectBefore) || shows(scene, aspectNow)) return;
  distance = std::max(distance, distanceToShow(scene, aspectNow));
}

void ViewReshape::apply(Camera& camera, const Bounds& scene, double aspectBefore,
                        double aspectNow) {
  const bool untouched =
      active_ && camera.target == left_.target && camera.distance == left_.distance &&
      camera.yawDegrees == left_.yawDegrees && camera.pitchDegrees == left_.pitchDegrees &&
      camera.ortho == left_.ortho && camera.fovYDegrees == left_.fovYDegrees;
  if (!untouched) {
    distance_ = camera.distance;
    aspect_ = aspectBefore;
  }
  active_ = true;
  camera.distance = distance_;
  camera.reshape(scene, aspect_, aspectNow);
  left_ = camera;
}

void Camera::setAxisView(AxisView view) {
  switch (view) {
    case AxisView::Front:
      yawDegrees = -90.0, pitchDegrees = 0.0;
      break;
    case AxisView::Back:
      yawDegrees = 90.0, pitchDegrees = 0.0;
      break;
    case AxisView::Right:
      yawDegrees = 0.0, pitchDegrees = 0.0;
      break;
    case AxisView::Left:
      yawDegrees = 180.0, pitchDegrees = 0.0;
      break;
    case AxisView::Top:
      yawDegrees = -90.0, pitchDegrees = 90.0;
      break;
    case AxisView::Bottom:
      yawDegrees = -90.0, pitchDegrees = -90.0;
      break;
  }
}

const char* Camera::axisViewName() const {
  const auto same = [](double a, double b) {
    return std::fabs(std::remainder(a - b, 360.0)) < 1e-6;
  };
  if (same(pitchDegrees, 90.0)) return same(yawDegrees, -90.0) ? "top" : "";
  if (same(pitchDegrees, -90.0)) return same(yawDegrees, -90.0) ? "bottom" : "";
  if (!same(pitchDegrees, 0.0)) return "";
  if (same(yawDegrees, -90.0)) return "front";
  if (same(yawDegrees, 90.0)) return "back";
  if (same(yawDegrees, 0.0)) return "right";
  if (same(yawDegrees, 180.0)) return "left";
  return "";
}

Ray Camera::rayThrough(glm::dvec2 pixel, glm::dvec2 size) const {
  double aspect = size.x / std::max(size.y, 1.0);
  double nx = 2.0 * pixel.x / std::max(size.x, 1.0) - 1.0;
  double ny = 1.0 - 2.0 * pixel.y / std::max(size.y, 1.0);
  double t = std::tan(radians(fovYDegrees) * 0.5);
  if (ortho) {
    double halfH = distance * t;
    glm::dvec3 origin = eye() + nx * halfH * aspect * right() + ny * halfH * up();
    return {origin - forward() * distance * 4.0, forward()};
  }
  glm::dvec3 dir = forward() + nx * t * aspect * right() + ny * t * up();
  return {eye(), glm::normalize(dir)};
}

}  // namespace strata::ui
