#include "engine/geometry/transform.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat3x3.hpp>

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

bool mirrors(const glm::dmat4& m) {
  return glm::determinant(glm::dmat3(m)) < 0.0;
}

}  // namespace strata
