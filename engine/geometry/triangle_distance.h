// The squared distance from a point to a triangle (its closest point, Ericson, "Real-Time
// Collision Detection", 5.1.5, by Voronoi regions), robust for degenerate triangles: a triangle
// with no area is measured as its three edges. Units are the caller's.
//
// Pure, header-only, any thread.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>

namespace strata {

inline double pointSegmentDistanceSquared(const glm::dvec3& p, const glm::dvec3& a,
                                          const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length2 = glm::dot(ab, ab);
  const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
  const glm::dvec3 d = p - (a + t * ab);
  return glm::dot(d, d);
}

// A triangle prepared for many point queries: what depends on the triangle alone is computed
// once. squared(p) is pointTriangleDistanceSquared(p, a, b, c) (the same function), and the
// same bits as squaredByRegions(p), the regions alone, on which it takes a shortcut: points well
// inside a triangle that is not a sliver get its plane's distance at once, as the regions would
// (the shortcut's margin, 1e-7 in barycentric weight, is far above the regions' rounding there,
// about 1e-16 * scale^2 / area^2: a sliver, n2 < 1e-6 scale^2, takes the regions).
class TriangleDistance {
 public:
  TriangleDistance() = default;
  TriangleDistance(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
      : a_(a), b_(b), c_(c), ab_(b - a), ac_(c - a), n_(glm::cross(ab_, ac_)) {
    n2_ = glm::dot(n_, n_);
    scale_ = std::max(glm::dot(ab_, ab_), glm::dot(ac_, ac_));
    flat_ = !(n2_ > 1e-24 * scale_ * scale_);
    shortcut_ = n2_ > 1e-6 * scale_ * scale_;
    if (shortcut_) {
      toB_ = glm::cross(ac_, n_) / n2_;
      toC_ = glm::cross(n_, ab_) / n2_;
    }
  }

  double squared(const glm::dvec3& p) const {
    if (shortcut_) {
      // Well inside the face, near its plane (most queries): the distance to the plane, as
      // the regions find it there, without them.
      const glm::dvec3 ap = p - a_;
      const double along = glm::dot(ap, n_);
      const double u = glm::dot(ap, toB_), v = glm::dot(ap, toC_);
      constexpr double kMargin = 1e-7;
      if (u > kMargin && v > kMargin && u + v < 1.0 - kMargin && along * along <= n2_ * scale_)
        return along * along / n2_;
    }
    return squaredByRegions(p);
  }

  // The regions alone (Ericson's closest point).
  double squaredByRegions(const glm::dvec3& p) const {
    const glm::dvec3 &a = a_, &b = b_, &c = c_, &ab = ab_, &ac = ac_;
    if (flat_)  // no area to speak of: the nearest of its edges
      return std::min({pointSegmentDistanceSquared(p, a, b), pointSegmentDistanceSquared(p, b, c),
                       pointSegmentDistanceSquared(p, c, a)});
    const glm::dvec3 ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    auto squaredTo = [&](const glm::dvec3& q) { return glm::dot(p - q, p - q); };
    if (d1 <= 0.0 && d2 <= 0.0) return squaredTo(a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return squaredTo(b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return squaredTo(a + ab * (d1 / (d1 - d3)));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return squaredTo(c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return squaredTo(a + ac * (d2 / (d2 - d6)));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
      return squaredTo(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    // Inside the face: the distance to its plane.
    const double along = glm::dot(ap, n_);
    return along * along / n2_;
  }

  const glm::dvec3& corner(int k) const { return k == 0 ? a_ : k == 1 ? b_ : c_; }

 private:
  glm::dvec3 a_{0.0}, b_{0.0}, c_{0.0}, ab_{0.0}, ac_{0.0}, n_{0.0};
  glm::dvec3 toB_{0.0}, toC_{0.0};  // dot(p - a, toB_): p's barycentric weight of b (c alike)
  double n2_ = 0.0, scale_ = 0.0;
  bool flat_ = true;
  bool shortcut_ = false;  // not a sliver: squared() may take the shortcut
};

inline double pointTriangleDistanceSquared(const glm::dvec3& p, const glm::dvec3& a,
                                           const glm::dvec3& b, const glm::dvec3& c) {
  return TriangleDistance(a, b, c).squared(p);
}

}  // namespace strata
