// Pattern operations: nodes that unite their children and repeat the union under a set of
// placements in the node's own frame (an array along a grid, copies around an axis, a mirror
// image). Each copy is a transform, not a copy of the subtree: the evaluator visits the children
// once per placement, so every edit of the source shows in every copy. What each pattern kind is
// called and which scene-file fields it has is in node_kinds.h; this file says what the
// parameters mean and which placements they make.
//
// Units: lengths in scene units, angles in degrees. Threads: pure functions.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "engine/kinds/node_kind.h"

namespace strata {

// Largest count along one axis of an array, or around a circular array (the product is limited
// by the scene's leaf limit, engine/document/expansion.h).
constexpr int kMaxPatternCount = 10000;
// Largest number of copies one pattern makes (an array's counts multiplied): the placements are
// listed, so even a pattern of nothing must stay small.
constexpr uint64_t kMaxPatternCopies = 1000000;

struct PatternParams {
  // Array: copies along x, y and z of the node's frame (each >= 1; (4, 1, 1) is a linear array)
  // and the distance from one copy to the next along each axis (may be negative).
  glm::ivec3 counts{1, 1, 1};
  glm::dvec3 step{0.0};
  // Circular array: copies around the axis through `center` along `axis` (>= 1), spread over
  // `angle` degrees: a full turn (+-360) spaces them evenly, any other angle puts the first and
  // the last `angle` apart. The first copy is the original.
  int count = 1;
  double angle = 360.0;
  // Circular array: the rotation axis; mirror: the plane's normal (0 x, 1 y, 2 z of the frame).
  int axis = 2;
  // Circular array: a point of the axis; mirror: a point of the plane (the node's frame).
  glm::dvec3 center{0.0};
  // Mirror: the original and its image (symmetry), or only the image.
  bool keepOriginal = true;

  bool operator==(const PatternParams& o) const {
    return counts == o.counts && step == o.step && count == o.count && angle == o.angle &&
           axis == o.axis && center == o.center && keepOriginal == o.keepOriginal;
  }
  bool operator!=(const PatternParams& o) const { return !(*this == o); }
};

// What changed from `before` to `after`, for people ("copies' count", "copies' step", "angle"):
// an undo says which field it takes back. "copies" where several changed.
// `pattern` names the fields as that kind reads them (a mirror's centre is its plane's position:
// its undo said "copies' centre", the circular array's word: an artist's test).
std::string patternChangeLabel(const PatternParams& before, const PatternParams& after,
                               Pattern pattern = Pattern::None);

// How many placements `pattern` makes (1 for Pattern::None); saturates at UINT64_MAX.
uint64_t patternCopies(Pattern pattern, const PatternParams& params);

// The placements, child frame to node frame, in order; the identity first whenever the
// original is kept. Pattern::None: the identity alone. Call checkPattern first.
std::vector<glm::dmat4> patternPlacements(Pattern pattern, const PatternParams& params);

// Throws strata::Error naming `who` when the parameters are not valid for `pattern`: counts
// outside [1, kMaxPatternCount] or more than kMaxPatternCopies copies, non-finite steps, angles or
// centres, an axis outside 0..2, an angle of 0 or beyond a full turn with more than one copy.
void checkPattern(Pattern pattern, const PatternParams& params, const std::string& who);

// The parameters of a new pattern holding parts of world size `heldSize` (scene units; zero
// when nothing is held): an array of 3 along x spaced a quarter of their width apart, 6 copies
// around z through the frame's origin, a mirror across the frame's yz plane keeping the
// original. Steps are rounded to two significant digits.
PatternParams defaultPattern(Pattern pattern, const glm::dvec3& heldSize);

// The placement under which a pattern shows its children first: the identity, except for a
// mirror that drops the original (its image). Invalid parameters give the identity.
glm::dmat4 firstPlacement(Pattern pattern, const PatternParams& params);

// "x", "y" or "z"; and back (false for anything else).
const char* axisName(int axis);
bool axisFromName(const std::string& name, int* axis);

}  // namespace strata
