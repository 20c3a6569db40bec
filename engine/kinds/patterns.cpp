#include "engine/kinds/patterns.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "engine/util/error.h"

namespace strata {
namespace {

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

uint64_t saturatingProduct(uint64_t a, uint64_t b) {
  if (a == 0 || b == 0) return 0;
  return a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

// A full turn (within rounding of the typed value): copies spaced evenly around it.
bool fullTurn(double angle) {
  return std::abs(std::abs(angle) - 360.0) < 1e-9;
}

}  // namespace

std::string patternChangeLabel(const PatternParams& before, const PatternParams& after,
                               Pattern pattern) {
  std::string label;
  int changes = 0;
  auto changed = [&](bool differs, const char* what) {
    if (differs) label = what, ++changes;
  };
  // A mirror's axis and centre are its plane's; a circular array's centre is its axis's point.
  const bool mirror = pattern == Pattern::Mirror;
  changed(before.counts != after.counts || before.count != after.count, "copies' count");
  changed(before.step != after.step, "copies' step");
  changed(before.angle != after.angle, "copies' angle");
  changed(before.axis != after.axis, mirror ? "mirror plane's direction" : "copies' axis");
  changed(before.center != after.center, mirror                         ? "mirror plane's position"
                                         : pattern == Pattern::Circular ? "axis position"
                                                                        : "copies' centre");
  changed(before.keepOriginal != after.keepOriginal, "keep the original");
  return changes == 1 ? label : "copies";
}

uint64_t patternCopies(Pattern pattern, const PatternParams& p) {
  switch (pattern) {
    case Pattern::Array:
      return saturatingProduct(
          saturatingProduct(uint64_t(std::max(p.counts.x, 0)), uint64_t(std::max(p.counts.y, 0))),
          uint64_t(std::max(p.counts.z, 0)));
    case Pattern::Circular:
      return uint64_t(std::max(p.count, 0));
    case Pattern::Mirror:
      return p.keepOriginal ? 2 : 1;
    default:
      return 1;
  }
}

std::vector<glm::dmat4> patternPlacements(Pattern pattern, const PatternParams& p) {
  const glm::dmat4 identity(1.0);
  std::vector<glm::dmat4> out;
  switch (pattern) {
    case Pattern::Array:
      for (int k = 0; k < p.counts.z; ++k)
        for (int j = 0; j < p.counts.y; ++j)
          for (int i = 0; i < p.counts.x; ++i)
            out.push_back(glm::translate(identity, glm::dvec3(i, j, k) * p.step));
      break;
    case Pattern::Circular: {
      glm::dvec3 axis(0.0);
      axis[p.axis] = 1.0;
      const double step = p.count <= 1        ? 0.0
                          : fullTurn(p.angle) ? p.angle / p.count
                                              : p.angle / (p.count - 1);
      for (int k = 0; k < p.count; ++k) {
        if (k == 0) {
          out.push_back(identity);
          continue;
        }
        glm::dmat4 m = glm::translate(identity, p.center);
        m = glm::rotate(m, glm::radians(step * k), axis);
        out.push_back(glm::translate(m, -p.center));
      }
      break;
    }
    case Pattern::Mirror: {
      if (p.keepOriginal) out.push_back(identity);
      glm::dvec3 flip(1.0);
      flip[p.axis] = -1.0;
      glm::dmat4 m = glm::translate(identity, p.center);
      m = glm::scale(m, flip);
      out.push_back(glm::translate(m, -p.center));
      break;
    }
    default:
      out.push_back(identity);
  }
  return out;
}

void checkPattern(Pattern pattern, const PatternParams& p, const std::string& who) {
  auto countOk = [](int n) { return n >= 1 && n <= kMaxPatternCount; };
  const std::string range = " must be a whole number from 1 to " + std::to_string(kMaxPatternCount);
  switch (pattern) {
    case Pattern::Array:
      for (int a = 0; a < 3; ++a)
        if (!countOk(p.counts[a]))
          throw Error(who + ": its count along " + axisName(a) + range + " (it is " +
                      std::to_string(p.counts[a]) + ")");
      if (patternCopies(pattern, p) > kMaxPatternCopies)
        throw Error(who + ": its counts make " + std::to_string(patternCopies(pattern, p)) +
                    " copies, more than " + std::to_string(kMaxPatternCopies));
      if (!finite3(p.step)) throw Error(who + ": its step is not a finite distance");
      break;
    case Pattern::Circular:
      if (!countOk(p.count))
        throw Error(who + ": its count" + range + " (it is " + std::to_string(p.count) + ")");
      if (!std::isfinite(p.angle) || std::abs(p.angle) > 360.0 + 1e-9 ||
          (p.angle == 0.0 && p.count > 1))
        throw Error(who +
                    ": its angle must be a number of degrees from -360 to 360, not 0 when it "
                    "has more than one copy");
      [[fallthrough]];
    case Pattern::Mirror:
      if (p.axis < 0 || p.axis > 2) throw Error(who + ": its axis must be x, y or z");
      if (!finite3(p.center)) throw Error(who + ": its centre is not a finite point");
      break;
    default:
      break;
  }
}

PatternParams defaultPattern(Pattern pattern, const glm::dvec3& heldSize) {
  PatternParams p;
  if (pattern == Pattern::Array) {
    p.counts = {3, 1, 1};
    double x = 1.25 * heldSize.x;
    if (!(x > 0.0) || !std::isfinite(x)) x = 1.0;
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    p.step = {std::ceil(x / unit) * unit, 0.0, 0.0};
  } else if (pattern == Pattern::Circular) {
    p.count = 6;
  } else if (pattern == Pattern::Mirror) {
    p.axis = 0;
  }
  return p;
}

glm::dmat4 firstPlacement(Pattern pattern, const PatternParams& params) {
  if (pattern != Pattern::Mirror || params.keepOriginal) return glm::dmat4(1.0);
  try {
    checkPattern(pattern, params, "");
  } catch (const Error&) {
    return glm::dmat4(1.0);
  }
  return patternPlacements(pattern, params).front();
}

const char* axisName(int axis) {
  return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

bool axisFromName(const std::string& name, int* axis) {
  for (int a = 0; a < 3; ++a)
    if (name == axisName(a)) {
      *axis = a;
      return true;
    }
  return false;
}

}  // namespace strata
