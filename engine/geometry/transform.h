// Node transforms: scale (negative components mirror), then rotate (Euler angles in degrees,
// applied about x, then y, then z), then translate. Units: scene units and degrees.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace strata {

struct Transform {
  glm::dvec3 translate{0.0};
  glm::dvec3 rotateDegrees{0.0};
  glm::dvec3 scale{1.0};

  // Object-to-parent matrix: T * Rz * Ry * Rx * S.
  glm::dmat4 matrix() const;
  bool operator==(const Transform& o) const {
    return translate == o.translate && rotateDegrees == o.rotateDegrees && scale == o.scale;
  }
  bool operator!=(const Transform& o) const { return !(*this == o); }
};

// The Transform whose matrix() is nearest `m` (an affine object-to-parent matrix): translate from
// its last column, scale from the lengths of its columns (the x column negated when it mirrors),
// rotation (Euler, degrees, in the matrix() convention) from the columns divided by them. Exact
// when the columns are orthogonal (no shear), which rigid motions and per-axis scales of an
// unsheared matrix keep. Angles under a nanodegree come back as 0.
Transform transformFromMatrix(const glm::dmat4& m);

// The Transform whose matrix() is `m`, keeping `like`'s rotation where `m`'s linear part is
// that rotation times a per-axis scale (a part scaled along its own axes, mirrored included:
// transformFromMatrix would turn a mirror into a half turn); else transformFromMatrix(m).
// *exact (when not null): whether the result's matrix() is `m` (to 1e-9 of its size): false
// where `m` shears, which no Transform holds (a turned part stretched along another axis).
Transform transformNear(const glm::dmat4& m, const Transform& like, bool* exact = nullptr);

// True when the matrix mirrors (negative determinant of its linear part): sampling must then
// reverse triangle winding to keep normals pointing outward.
bool mirrors(const glm::dmat4& m);

}  // namespace strata
