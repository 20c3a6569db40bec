#include "engine/geometry/transform.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>

namespace strata {

glm::dmat4 Transform::matrix() const {
  glm::dmat4 m(1.0);
  m = glm::translate(m, translate);
  m = glm::rotate(m, glm::radians(rotateDegrees.z), glm::dvec3(0, 0, 1));
  m = glm::rotate(m, glm::radians(rotateDegrees.y), glm::dvec3(0, 1, 0));
  m = glm::rotate(m, glm::radians(rotateDegrees.x), glm::dvec3(1, 0, 0));
  m = glm::scale(m, scale);
  return m;
}

Transform transformFromMatrix(const glm::dmat4& m) {
  Transform t;
  t.translate = glm::dvec3(m[3]);
  glm::dvec3 columns[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
  for (int i = 0; i < 3; ++i) t.scale[i] = glm::length(columns[i]);
  if (mirrors(m)) t.scale.x = -t.scale.x;
  glm::dmat3 r(1.0);
  for (int i = 0; i < 3; ++i)
    if (t.scale[i] != 0.0) r[i] = columns[i] / t.scale[i];
  // The lengths of turned columns come out a rounding away from whole scales (0.9999999999999999
  // for 1, saved so by a part turned onto a surface): a scale within 1e-12 of a whole number is
  // that number (the matrix it makes differs by a rounding).
  for (int i = 0; i < 3; ++i) {
    const double whole = std::round(t.scale[i]);
    if (whole != 0.0 && std::fabs(t.scale[i] - whole) < 1e-12 * std::fabs(whole))
      t.scale[i] = whole;
  }
  // r = Rz(c) * Ry(b) * Rx(a): r[col][row]; r[0][2] = -sin(b).
  const double sinB = -std::clamp(r[0][2], -1.0, 1.0);
  double a, b = std::asin(sinB), c;
  if (std::fabs(sinB) < 1.0 - 1e-12) {
    a = std::atan2(r[1][2], r[2][2]);
    c = std::atan2(r[0][1], r[0][0]);
  } else {  // gimbal lock: x and z turn about the same axis; all of it on z
    a = 0.0;
    c = std::atan2(-r[1][0], r[1][1]);
  }
  t.rotateDegrees = glm::degrees(glm::dvec3(a, b, c));
  // Rounding leaves angles such as -1e-15 where none was meant (shown as "-0.00"): angles below
  // a nanodegree are none.
  for (int i = 0; i < 3; ++i)
    if (std::fabs(t.rotateDegrees[i]) < 1e-9) t.rotateDegrees[i] = 0.0;
  return t;
}

namespace {
// Whether a and b agree to 1e-9 of `size` in every entry of their linear parts, and of the
// larger of `size` and the translation's in their translations (a part far from the origin
// keeps the linear part's own tolerance: a shear there is not hidden by its distance).
bool near(const glm::dmat4& a, const glm::dmat4& b, double size) {
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (std::fabs(a[c][r] - b[c][r]) > 1e-9 * size) return false;
  const double far = std::max({size, std::fabs(b[3][0]), std::fabs(b[3][1]), std::fabs(b[3][2])});
  for (int r = 0; r < 3; ++r)
    if (std::fabs(a[3][r] - b[3][r]) > 1e-9 * far) return false;
  return true;
}
}  // namespace

Transform transformNear(const glm::dmat4& m, const Transform& like, bool* exact) {
  double size = 1e-300;  // of the linear part
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) size = std::max(size, std::fabs(m[c][r]));
  Transform kept = like;
  kept.translate = glm::dvec3(m[3]);
  kept.scale = glm::dvec3(1.0);
  // S = R^T L: diagonal where `m` is `like`'s rotation times a per-axis scale.
  const glm::dmat3 s = glm::transpose(glm::dmat3(kept.matrix())) * glm::dmat3(m);
  kept.scale = glm::dvec3(s[0][0], s[1][1], s[2][2]);
  if (kept.scale.x != 0.0 && kept.scale.y != 0.0 && kept.scale.z != 0.0 &&
      near(kept.matrix(), m, size)) {
    if (exact) *exact = true;
    return kept;
  }
  const Transform t = transformFromMatrix(m);
  if (exact) *exact = near(t.matrix(), m, size);
  return t;
}

bool mirrors(const glm::dmat4& m) {
  return glm::determinant(glm::dmat3(m)) < 0.0;
}

}  // namespace strata
