#include "ui/gizmo.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat2x2.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace strata::ui {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kHandlePixels = 90.0;  // length of a handle on screen
constexpr double kPickPixels = 9.0;

const glm::vec4 kAxisColors[3] = {
    {0.93f, 0.27f, 0.30f, 1.0f}, {0.45f, 0.82f, 0.25f, 1.0f}, {0.25f, 0.55f, 0.98f, 1.0f}};
const glm::vec4 kHot{1.0f, 0.85f, 0.25f, 1.0f};

glm::dmat3 rotationX(double deg) {
  return glm::dmat3(glm::rotate(glm::dmat4(1.0), deg * kPi / 180.0, glm::dvec3(1, 0, 0)));
}
glm::dmat3 rotationY(double deg) {
  return glm::dmat3(glm::rotate(glm::dmat4(1.0), deg * kPi / 180.0, glm::dvec3(0, 1, 0)));
}
glm::dmat3 rotationZ(double deg) {
  return glm::dmat3(glm::rotate(glm::dmat4(1.0), deg * kPi / 180.0, glm::dvec3(0, 0, 1)));
}

double segmentDistance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  glm::dvec2 ab = b - a;
  double len2 = glm::dot(ab, ab);
  double t = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

double snapTo(double value, double step) {
  return step > 0 ? std::round(value / step) * step : value;
}

glm::dvec3 safeNormalize(const glm::dvec3& v, const glm::dvec3& fallback) {
  double l = glm::length(v);
  return l > 1e-12 ? v / l : fallback;
}

void appendQuad(std::vector<LineVertex>* tris, glm::dvec3 a, glm::dvec3 b, glm::dvec3 side,
                const glm::vec4& color) {
  LineVertex v[4] = {lineVertex(a - side, color), lineVertex(a + side, color),
                     lineVertex(b + side, color), lineVertex(b - side, color)};
  for (int i : {0, 1, 2, 0, 2, 3}) tris->push_back(v[i]);
}

}  // namespace

bool ScreenMapping::toScreen(const glm::dvec3& world, glm::dvec2* pixel) const {
  glm::dvec4 clip = viewProjection * glm::dvec4(world, 1.0);
  if (clip.w <= 1e-12) return false;
  glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
  *pixel = glm::dvec2((ndc.x * 0.5 + 0.5) * size.x, (0.5 - ndc.y * 0.5) * size.y);
  return true;
}

void Gizmo::place(const glm::dmat4& parentWorld, const Transform& transform) {
  parentWorld_ = parentWorld;
  transform_ = transform;
  origin_ = glm::dvec3(parentWorld * glm::dvec4(transform.translate, 1.0));
}

glm::dvec3 Gizmo::handleAxis(int k) const {
  glm::dmat3 parent(parentWorld_);
  glm::dvec3 unit(0.0);
  unit[k] = 1.0;
  const glm::dvec3 d = transform_.rotateDegrees;
  switch (mode) {
    case GizmoMode::Move:
      return safeNormalize(parent * unit, unit);
    case GizmoMode::Scale:
      return safeNormalize(parent * rotationZ(d.z) * rotationY(d.y) * rotationX(d.x) * unit, unit);
    case GizmoMode::Rotate:
      if (k == 2) return safeNormalize(parent * unit, unit);
      if (k == 1) return safeNormalize(parent * rotationZ(d.z) * unit, unit);
      return safeNormalize(parent * rotationZ(d.z) * rotationY(d.y) * unit, unit);
  }
  return unit;
}

double Gizmo::handleLength(const ScreenMapping& view) const {
  double upp = view.unitsPerPixel;
  if (!view.ortho) {
    // Constant size on screen: scale with the gizmo's distance along the view direction.
    double depth = glm::dot(origin_ - view.eye, view.forward);
    upp = std::max(depth, 1e-9) * view.unitsPerPixel;
  }
  return kHandlePixels * upp;
}

void Gizmo::ringBasis(int k, glm::dvec3* a, glm::dvec3* b) const {
  const glm::dvec3 n = handleAxis(k);
  *a =
      safeNormalize(glm::cross(n, std::fabs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)),
                    glm::dvec3(1, 0, 0));
  *b = glm::cross(n, *a);
}

double Gizmo::ringRadius(const ScreenMapping& view) const {
  return handleLength(view) * 0.85;
}

std::vector<glm::dvec3> Gizmo::ring(int k, const ScreenMapping& view) const {
  glm::dvec3 a, b;
  ringBasis(k, &a, &b);
  const double r = ringRadius(view);
  std::vector<glm::dvec3> points;
  for (int i = 0; i <= 64; ++i) {
    double t = 2.0 * kPi * i / 64.0;
    points.push_back(origin_ + r * (std::cos(t) * a + std::sin(t) * b));
  }
  return points;
}

bool Gizmo::ringBackSegment(const ScreenMapping& view, const glm::dvec3& p,
                            const glm::dvec3& q) const {
  const glm::dvec3 towardViewer =
      view.ortho ? -view.forward : safeNormalize(view.eye - origin_, -view.forward);
  // Beyond a sixth of the radius: a ring nearly facing the viewer (tilted under about 10
  // degrees, as a perspective view turns one off the screen's middle) stays whole.
  const double margin = ringRadius(view) / 6.0;
  return glm::dot(0.5 * (p + q) - origin_, towardViewer) < -margin;
}

int Gizmo::hover(const ScreenMapping& view, glm::dvec2 mouse) const {
  glm::dvec2 o;
  if (!view.toScreen(origin_, &o)) return -1;
  int best = -1;
  double bestScore = 1e300;
  // A ring's back half, where no front half is near: a click there took the ring's faint half
  // for empty space and deselected the part (an artist's test).
  int nearestBack = -1;
  double nearestBackDistance = kPickPixels;
  for (int k = 0; k < 3; ++k) {
    double d = 1e300;
    if (mode == GizmoMode::Rotate) {
      auto points = ring(k, view);
      glm::dvec2 prev;
      bool havePrev = false;
      for (size_t i = 0; i < points.size(); ++i) {
        glm::dvec2 s;
        if (!view.toScreen(points[i], &s)) {
          havePrev = false;
          continue;
        }
        if (havePrev) {
          const double distance = segmentDistance(mouse, prev, s);
          if (!ringBackSegment(view, points[i - 1], points[i]))
            d = std::min(d, distance);
          else if (distance < nearestBackDistance) {
            nearestBackDistance = distance;
            nearestBack = k;
          }
        }
        prev = s;
        havePrev = true;
      }
    } else {
      glm::dvec2 tip;
      if (!view.toScreen(origin_ + handleAxis(k) * handleLength(view), &tip)) continue;
      d = segmentDistance(mouse, o + (tip - o) * 0.15, tip);
    }
    // Where rings cross on screen (an edge-on ring is a line through the others), the one
    // facing the viewer more is taken: dragging an edge-on ring across its line turns nothing.
    double score = d;
    if (mode == GizmoMode::Rotate) {
      const glm::dvec3 towardViewer =
          view.ortho ? -view.forward : safeNormalize(view.eye - origin_, -view.forward);
      score -= 4.0 * std::fabs(glm::dot(handleAxis(k), towardViewer));
    }
    if (d < kPickPixels && score < bestScore) {
      bestScore = score;
      best = k;
    }
  }
  return best >= 0 ? best : nearestBack;
}

double Gizmo::ringTurnDegrees(const ScreenMapping& view, glm::dvec2 o, glm::dvec2 mouse) const {
  // The ring on screen: o + A (cos t, sin t), A's columns the screen images of its radii along
  // a and b (ring()); t turns from a towards b, a positive turn about the ring's axis.
  const glm::dvec3 n = handleAxis(axis_);
  glm::dvec3 a, b;
  ringBasis(axis_, &a, &b);
  const double r = ringRadius(view);
  glm::dvec2 pa, pb;
  if (view.toScreen(origin_ + r * a, &pa) && view.toScreen(origin_ + r * b, &pb)) {
    const glm::dmat2 A(pa - o, pb - o);
    const double det = glm::determinant(A);
    const double major = std::max(glm::length(pa - o), glm::length(pb - o));
    if (major > 1e-9) {
      const double flatness = std::fabs(det) / (major * major);  // minor / major axis, about
      if (flatness > 0.3) {
        // Facing the viewer enough: the cursor's angle on the ellipse, so the ring follows it.
        const glm::dmat2 inverse = glm::inverse(A);
        const glm::dvec2 s = inverse * (startMouse_ - o), m = inverse * (mouse - o);
        return std::remainder(std::atan2(m.y, m.x) - std::atan2(s.y, s.x), 2.0 * kPi) * 180.0 / kPi;
      }
      // Seen nearly edge-on: along the ring's tangent at the point grabbed, a turn of one
      // radian for each radius's length on screen moved along it.
      // The point grabbed: the ring's nearest to the cursor on screen, of two about as near
      // (its front and back project onto each other) the one nearer the viewer.
      constexpr int kSamples = 256;
      double distance[kSamples], bestDistance = 1e300;
      for (int i = 0; i < kSamples; ++i) {
        const double t = 2.0 * kPi * i / kSamples;
        distance[i] = glm::length(o + A * glm::dvec2(std::cos(t), std::sin(t)) - startMouse_);
        bestDistance = std::min(bestDistance, distance[i]);
      }
      double grabbed = 0.0, nearest = 1e300;
      for (int i = 0; i < kSamples; ++i) {
        if (distance[i] > bestDistance + 3.0) continue;
        const double t = 2.0 * kPi * i / kSamples;
        const glm::dvec3 p = origin_ + r * (std::cos(t) * a + std::sin(t) * b);
        const double depth = view.ortho ? glm::dot(p, view.forward) : glm::length(p - view.eye);
        if (depth < nearest) {
          nearest = depth;
          grabbed = t;
        }
      }
      const glm::dvec2 tangent = A * glm::dvec2(-std::sin(grabbed), std::cos(grabbed));
      const double pixelsPerRadian = glm::length(tangent);
      if (pixelsPerRadian > 0.05 * major) {
        // Across the line too, whichever way the drag went first: dragged across, an edge-on
        // ring turned 0 degrees, and most people drag across first (an artist's test). Across
        // is the tangent turned a quarter clockwise on screen (y down): right of the way along.
        const glm::dvec2 moved = mouse - startMouse_;
        const glm::dvec2 across(-tangent.y, tangent.x);
        const double alongPixels = glm::dot(moved, tangent) / pixelsPerRadian,
                     acrossPixels = glm::dot(moved, across) / pixelsPerRadian;
        if (edgeOnWay_ == 0 && glm::length(moved) >= 4.0)
          edgeOnWay_ = std::fabs(acrossPixels) > std::fabs(alongPixels) ? 2 : 1;
        const double pixels = edgeOnWay_ == 2 ? acrossPixels : alongPixels;
        return pixels / pixelsPerRadian * 180.0 / kPi;
      }
    }
  }
  // Grabbed where the ring runs towards the viewer: the cursor's angle about the centre.
  const glm::dvec2 a0 = startMouse_ - o, b0 = mouse - o;
  double delta = (std::atan2(b0.y, b0.x) - std::atan2(a0.y, a0.x)) * 180.0 / kPi;
  // Screen y points down: a counter-clockwise turn on screen is a negative angle here. It is
  // a positive rotation about an axis that points at the viewer.
  const glm::dvec3 towardViewer = view.ortho ? -view.forward : glm::normalize(view.eye - origin_);
  if (glm::dot(n, towardViewer) > 0) delta = -delta;
  return std::remainder(delta, 360.0);
}

void Gizmo::begin(int axis, const ScreenMapping&, glm::dvec2 mouse) {
  axis_ = axis;
  start_ = transform_;
  startMouse_ = mouse;
  edgeOnWay_ = 0;
}

Transform Gizmo::drag(const ScreenMapping& view, glm::dvec2 mouse, const GizmoSnap& snap) const {
  Transform t = start_;
  if (axis_ < 0) return t;
  const int k = axis_;
  glm::dvec2 o, tip;
  const double length = handleLength(view);
  if (!view.toScreen(origin_, &o)) return t;
  if (mode == GizmoMode::Rotate) {
    const double delta = ringTurnDegrees(view, o, mouse);
    double angle = start_.rotateDegrees[k] + delta;
    angle = std::remainder(angle, 360.0);
    t.rotateDegrees[k] = snap.enabled ? snapTo(angle, snap.degrees) : angle;
    return t;
  }
  if (!view.toScreen(origin_ + handleAxis(k) * length, &tip)) return t;
  glm::dvec2 axisScreen = tip - o;
  double pixelsPerUnit = glm::length(axisScreen) / length;
  if (pixelsPerUnit < 1e-6) return t;  // the axis points at the viewer
  glm::dvec2 dir = axisScreen / glm::length(axisScreen);
  double along = glm::dot(mouse - startMouse_, dir) / pixelsPerUnit;  // world units
  if (mode == GizmoMode::Move) {
    glm::dvec3 unit(0.0);
    unit[k] = 1.0;
    double parentScale = glm::length(glm::dmat3(parentWorld_) * unit);
    double value = start_.translate[k] + along / std::max(parentScale, 1e-12);
    t.translate[k] = snap.enabled ? snapTo(value, snap.step) : value;
  } else {
    double startAlong = glm::dot(startMouse_ - o, dir) / pixelsPerUnit;
    if (std::fabs(startAlong) < 1e-9) return t;
    double factor = (startAlong + along) / startAlong;
    double value = start_.scale[k] * factor;
    if (snap.enabled) value = snapTo(value, 0.1);
    if (std::fabs(value) < 1e-6) value = value < 0 ? -1e-6 : 1e-6;  // never zero
    t.scale[k] = value;
  }
  return t;
}

bool Gizmo::screenBox(const ScreenMapping& view, ScreenBox* box) const {
  std::vector<LineVertex> lines, triangles;
  appendGeometry(view, -1, &lines, &triangles);
  bool any = false;
  for (const std::vector<LineVertex>* list : {&lines, &triangles})
    for (const LineVertex& v : *list) {
      glm::dvec2 p;
      if (!view.toScreen(glm::dvec3(v.position[0], v.position[1], v.position[2]), &p)) continue;
      box->lo = any ? glm::min(box->lo, p) : p;
      box->hi = any ? glm::max(box->hi, p) : p;
      any = true;
    }
  const double margin = 4.0;
  box->lo -= margin;
  box->hi += margin;
  return any;
}

void Gizmo::appendGeometry(const ScreenMapping& view, int hot, std::vector<LineVertex>* lines,
                           std::vector<LineVertex>* triangles) const {
  const double length = handleLength(view);
  const double upp = length / kHandlePixels;  // world units per pixel at the gizmo
  for (int k = 0; k < 3; ++k) {
    glm::vec4 color = (k == hot || k == axis_) ? kHot : kAxisColors[k];
    glm::dvec3 axis = handleAxis(k);
    glm::dvec3 toViewer =
        view.ortho ? -view.forward : safeNormalize(view.eye - origin_, -view.forward);
    if (mode == GizmoMode::Rotate) {
      auto points = ring(k, view);
      for (size_t i = 0; i + 1 < points.size(); ++i) {
        const bool back = ringBackSegment(view, points[i], points[i + 1]);
        glm::dvec3 tangent = points[i + 1] - points[i];
        glm::dvec3 side =
            safeNormalize(glm::cross(tangent, toViewer), axis) * upp * (back ? 0.75 : 1.5);
        glm::vec4 shade = color;
        if (back) shade.a *= 0.3f;  // faint: seen, not picked (hover)
        appendQuad(triangles, points[i], points[i + 1], side, shade);
      }
      continue;
    }
    glm::dvec3 start = origin_ + axis * length * 0.15;
    glm::dvec3 tip = origin_ + axis * length;
    glm::dvec3 side = safeNormalize(glm::cross(axis, toViewer), glm::dvec3(0, 0, 1));
    appendQuad(triangles, start, tip - axis * length * 0.12, side * upp * 1.5, color);
    if (mode == GizmoMode::Move) {
      // Arrow head: a triangle facing the viewer.
      glm::dvec3 base = tip - axis * length * 0.2;
      triangles->push_back(lineVertex(base - side * upp * 7.0, color));
      triangles->push_back(lineVertex(base + side * upp * 7.0, color));
      triangles->push_back(lineVertex(tip, color));
    } else {
      glm::dvec3 up = safeNormalize(glm::cross(side, toViewer), axis) * upp * 6.0;
      glm::dvec3 c = tip - axis * length * 0.06;
      LineVertex v[4] = {lineVertex(c - side * upp * 6.0 - up, color),
                         lineVertex(c + side * upp * 6.0 - up, color),
                         lineVertex(c + side * upp * 6.0 + up, color),
                         lineVertex(c - side * upp * 6.0 + up, color)};
      for (int i : {0, 1, 2, 0, 2, 3}) triangles->push_back(v[i]);
    }
  }
  // A small centre mark.
  glm::vec4 white(1.0f, 1.0f, 1.0f, 0.9f);
  glm::dvec3 r = safeNormalize(glm::cross(view.forward, glm::dvec3(0, 0, 1)), glm::dvec3(1, 0, 0));
  glm::dvec3 u = safeNormalize(glm::cross(r, view.forward), glm::dvec3(0, 0, 1));
  double s = upp * 4.0;
  lines->push_back(lineVertex(origin_ - r * s, white));
  lines->push_back(lineVertex(origin_ + r * s, white));
  lines->push_back(lineVertex(origin_ - u * s, white));
  lines->push_back(lineVertex(origin_ + u * s, white));
}

}  // namespace strata::ui
