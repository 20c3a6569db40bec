#include "engine/geometry/primitives.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/util/error.h"

namespace strata {
namespace {
constexpr double kPi = 3.14159265358979323846;

// Builds a closed surface of revolution about z from a profile polyline (r_i, z_i), i = 0..n-1,
// running from the bottom to the top. Profile points with r == 0 become single pole vertices.
// Faces are oriented outward when the profile runs bottom to top with r >= 0.
TriangleMesh revolve(const std::vector<glm::dvec2>& profile, int segments) {
  TriangleMesh mesh;
  std::vector<int> ringStart(profile.size());
  for (size_t i = 0; i < profile.size(); ++i) {
    ringStart[i] = int(mesh.positions.size());
    if (profile[i].x == 0.0) {
      mesh.positions.push_back({0.0, 0.0, profile[i].y});
    } else {
      for (int s = 0; s < segments; ++s) {
        double phi = 2.0 * kPi * s / segments;
        mesh.positions.push_back(
            {profile[i].x * std::cos(phi), profile[i].x * std::sin(phi), profile[i].y});
      }
    }
  }
  auto vertex = [&](size_t ring, int s) -> uint32_t {
    if (profile[ring].x == 0.0) return uint32_t(ringStart[ring]);
    return uint32_t(ringStart[ring] + (s % segments));
  };
  for (size_t i = 0; i + 1 < profile.size(); ++i) {
    bool lowPole = profile[i].x == 0.0, highPole = profile[i + 1].x == 0.0;
    for (int s = 0; s < segments; ++s) {
      uint32_t a = vertex(i, s), b = vertex(i, s + 1);
      uint32_t c = vertex(i + 1, s + 1), d = vertex(i + 1, s);
      // Quad a b c d is counter-clockwise seen from outside (phi grows to the left, z up).
      if (!lowPole) mesh.triangles.push_back({a, b, c});
      if (!highPole) mesh.triangles.push_back({a, c, d});
      if (lowPole && highPole) break;
    }
  }
  return mesh;
}

void requirePositive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string("primitive parameter ") + what + " must be a positive number");
}

std::vector<glm::dvec2> arc(double cx, double cz, double r, double from, double to, int steps) {
  std::vector<glm::dvec2> points;
  for (int k = 0; k <= steps; ++k) {
    double t = from + (to - from) * k / steps;
    points.push_back({cx + r * std::cos(t), cz + r * std::sin(t)});
  }
  return points;
}
}  // namespace

int autoSegments(double worldRadius, double maxError) {
  if (!(worldRadius > 0.0) || !(maxError > 0.0)) return 12;
  if (maxError >= worldRadius) return 12;
  double n = kPi / std::acos(1.0 - maxError / worldRadius);
  if (!std::isfinite(n)) return kMaxAutoSegments;
  return std::clamp(int(std::ceil(n)), 12, kMaxAutoSegments);
}

double primitiveRadius(NodeKind kind, const PrimitiveParams& p) {
  switch (kind) {
    case NodeKind::Sphere:
    case NodeKind::Cylinder:
    case NodeKind::Capsule:
      return p.radius;
    case NodeKind::Cone:
      return std::max(p.radius, p.topRadius);
    case NodeKind::Torus:
      return p.majorRadius + p.minorRadius;
    default:
      return 0.0;
  }
}

TriangleMesh tessellatePrimitive(NodeKind kind, const PrimitiveParams& p, int segments) {
  segments = std::max(3, segments);
  switch (kind) {
    case NodeKind::Box: {
      for (int a = 0; a < 3; ++a) requirePositive(p.size[a], "size");
      TriangleMesh mesh;
      glm::dvec3 h = p.size * 0.5;
      for (int i = 0; i < 8; ++i)
        mesh.positions.push_back({i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z});
      const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                    {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
      for (const auto& f : faces) {
        mesh.triangles.push_back({f[0], f[1], f[2]});
        mesh.triangles.push_back({f[0], f[2], f[3]});
      }
      return mesh;
    }
    case NodeKind::Sphere: {
      requirePositive(p.radius, "radius");
      int rings = std::max(2, segments / 2);
      std::vector<glm::dvec2> profile;
      for (int k = 0; k <= rings; ++k) {
        double theta = -kPi / 2 + kPi * k / rings;
        double r = (k == 0 || k == rings) ? 0.0 : p.radius * std::cos(theta);
        profile.push_back({r, p.radius * std::sin(theta)});
      }
      return revolve(profile, segments);
    }
    case NodeKind::Cylinder:
      requirePositive(p.radius, "radius");
      requirePositive(p.height, "height");
      return revolve({{0.0, -p.height / 2},
                      {p.radius, -p.height / 2},
                      {p.radius, p.height / 2},
                      {0.0, p.height / 2}},
                     segments);
    case NodeKind::Cone: {
      requirePositive(p.radius, "radius");
      requirePositive(p.height, "height");
      if (!(p.topRadius >= 0.0) || !std::isfinite(p.topRadius))
        throw Error("primitive parameter topRadius must be zero or positive");
      std::vector<glm::dvec2> profile = {{0.0, -p.height / 2}, {p.radius, -p.height / 2}};
      if (p.topRadius > 0.0) profile.push_back({p.topRadius, p.height / 2});
      profile.push_back({0.0, p.height / 2});
      return revolve(profile, segments);
    }
    case NodeKind::Torus: {
      requirePositive(p.majorRadius, "majorRadius");
      requirePositive(p.minorRadius, "minorRadius");
      if (!(p.minorRadius < p.majorRadius))
        throw Error("primitive parameter minorRadius must be smaller than majorRadius");
      // Tube segments scaled to the tube's share of the outer radius, for an even chord error.
      int tube = std::max(
          8, int(std::ceil(segments * std::sqrt(p.minorRadius / (p.majorRadius + p.minorRadius)))));
      TriangleMesh mesh;
      for (int i = 0; i < segments; ++i) {
        double phi = 2.0 * kPi * i / segments;
        for (int j = 0; j < tube; ++j) {
          double theta = 2.0 * kPi * j / tube;
          double r = p.majorRadius + p.minorRadius * std::cos(theta);
          mesh.positions.push_back(
              {r * std::cos(phi), r * std::sin(phi), p.minorRadius * std::sin(theta)});
        }
      }
      for (int i = 0; i < segments; ++i)
        for (int j = 0; j < tube; ++j) {
          uint32_t a = uint32_t(i * tube + j), b = uint32_t(((i + 1) % segments) * tube + j);
          uint32_t c = uint32_t(((i + 1) % segments) * tube + (j + 1) % tube);
          uint32_t d = uint32_t(i * tube + (j + 1) % tube);
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
        }
      return mesh;
    }
    case NodeKind::Capsule: {
      requirePositive(p.radius, "radius");
      if (!(p.height >= 0.0) || !std::isfinite(p.height))
        throw Error("primitive parameter height must be zero or positive");
      int quarter = std::max(2, segments / 4);
      auto bottom = arc(0.0, -p.height / 2, p.radius, -kPi / 2, 0.0, quarter);
      auto top = arc(0.0, p.height / 2, p.radius, 0.0, kPi / 2, quarter);
      bottom.front().x = 0.0;
      top.back().x = 0.0;
      if (p.height == 0.0) top.erase(top.begin());  // the equators coincide: keep one
      bottom.insert(bottom.end(), top.begin(), top.end());
      return revolve(bottom, segments);
    }
    default:
      throw Error(std::string("internal: ") + kindName(kind) + " is not a primitive");
  }
}

}  // namespace strata
