// The primitive table and each primitive's tessellation.
#include "engine/kinds/primitives.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
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

std::vector<glm::dvec2> arc(double cx, double cz, double r, double from, double to, int steps) {
  std::vector<glm::dvec2> points;
  for (int k = 0; k <= steps; ++k) {
    double t = from + (to - from) * k / steps;
    points.push_back({cx + r * std::cos(t), cz + r * std::sin(t)});
  }
  return points;
}

// Adds positions, welding identical ones; drops triangles that weld to fewer than three
// distinct vertices.
class WeldingMesh {
 public:
  uint32_t vertex(const glm::dvec3& p) {
    auto [it, added] = index_.try_emplace({p.x, p.y, p.z}, uint32_t(mesh_.positions.size()));
    if (added) mesh_.positions.push_back(p);
    return it->second;
  }
  void triangle(uint32_t a, uint32_t b, uint32_t c) {
    if (a != b && b != c && a != c) mesh_.triangles.push_back({a, b, c});
  }
  // Quad a b c d, counter-clockwise seen from outside.
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  TriangleMesh take() { return std::move(mesh_); }

 private:
  TriangleMesh mesh_;
  std::map<std::array<double, 3>, uint32_t> index_;
};

// The shortest of %.15g / %.17g that reads back as `value`.
std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.15g", value);
  if (std::strtod(text, nullptr) != value) std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

// ---- box ---------------------------------------------------------------------------------

TriangleMesh boxMesh(const PrimitiveParams& p, int) {
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

// ---- sphere, cylinder, cone, capsule: surfaces of revolution ------------------------------

TriangleMesh sphereMesh(const PrimitiveParams& p, int segments) {
  int rings = std::max(2, segments / 2);
  std::vector<glm::dvec2> profile;
  for (int k = 0; k <= rings; ++k) {
    double theta = -kPi / 2 + kPi * k / rings;
    double r = (k == 0 || k == rings) ? 0.0 : p.radius * std::cos(theta);
    profile.push_back({r, p.radius * std::sin(theta)});
  }
  return revolve(profile, segments);
}

TriangleMesh cylinderMesh(const PrimitiveParams& p, int segments) {
  return revolve({{0.0, -p.height / 2},
                  {p.radius, -p.height / 2},
                  {p.radius, p.height / 2},
                  {0.0, p.height / 2}},
                 segments);
}

// Either end may be pointed (a countersink is a cone standing on its tip), not both.
TriangleMesh coneMesh(const PrimitiveParams& p, int segments) {
  std::vector<glm::dvec2> profile = {{0.0, -p.height / 2}};
  if (p.radius > 0.0) profile.push_back({p.radius, -p.height / 2});
  if (p.topRadius > 0.0) profile.push_back({p.topRadius, p.height / 2});
  profile.push_back({0.0, p.height / 2});
  return revolve(profile, segments);
}

TriangleMesh capsuleMesh(const PrimitiveParams& p, int segments) {
  int quarter = std::max(2, segments / 4);
  auto bottom = arc(0.0, -p.height / 2, p.radius, -kPi / 2, 0.0, quarter);
  auto top = arc(0.0, p.height / 2, p.radius, 0.0, kPi / 2, quarter);
  bottom.front().x = 0.0;
  top.back().x = 0.0;
  if (p.height == 0.0) top.erase(top.begin());  // the equators coincide: keep one
  bottom.insert(bottom.end(), top.begin(), top.end());
  return revolve(bottom, segments);
}

// ---- torus -------------------------------------------------------------------------------

TriangleMesh torusMesh(const PrimitiveParams& p, int segments) {
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

// The largest number below `bound` (> 0) written with 4 significant digits: a fitted parameter
// strictly within a strict relation, shown as kept.
double largestBelow(double bound) {
  // The digits of the largest number below it: 9.999 under 10, not 9.99 (10's own digits).
  const double unit = std::pow(10.0, std::floor(std::log10(std::nextafter(bound, 0.0))) - 3.0);
  const auto fourDigits = [](double v) {  // 1.999 rather than 1.9990000000000001
    char text[32];
    std::snprintf(text, sizeof(text), "%.4g", v);
    return std::strtod(text, nullptr);
  };
  double v = fourDigits(std::floor(bound / unit) * unit);
  if (v >= bound) v = fourDigits(v - unit);
  return v;
}

ParamProblem torusRelations(const PrimitiveParams& p) {
  if (p.minorRadius < p.majorRadius) return {};
  return {"minorRadius (" + shortNumber(p.minorRadius) + ") must be smaller than majorRadius (" +
              shortNumber(p.majorRadius) + ")",
          {"minorRadius", "majorRadius"}};
}

// ---- rounded box -------------------------------------------------------------------------

// The box of `size` whose edges and corners are rounded with `radius`: the Minkowski sum of
// the inner box (size - 2 radius) and a sphere. A latitude-longitude sphere whose quarter
// meridians and equator are doubled, each copy pushed to its octant's corner of the inner box;
// the flat faces are the quads that open between the copies.
TriangleMesh roundedBoxMesh(const PrimitiveParams& p, int segments) {
  const int q = std::max(2, segments / 4);  // steps per quarter circle
  const glm::dvec3 inner = p.size * 0.5 - glm::dvec3(p.radius);
  // Columns: 4 quadrants of q + 1 longitudes (both ends), rows: 2 hemispheres of q + 1
  // latitudes (both ends). Poles and doubled seams weld or open into the flat faces.
  const int cols = 4 * (q + 1), rows = 2 * (q + 1);
  WeldingMesh mesh;
  std::vector<uint32_t> ids(size_t(cols) * rows);
  for (int c = 0; c < cols; ++c) {
    const int quadrant = c / (q + 1), step = c % (q + 1);
    const double phi = kPi / 2 * (quadrant + double(step) / q);
    const double sx = (quadrant == 0 || quadrant == 3) ? 1.0 : -1.0;
    const double sy = quadrant <= 1 ? 1.0 : -1.0;
    for (int r = 0; r < rows; ++r) {
      const int half = r / (q + 1), k = r % (q + 1);
      const double theta = kPi / 2 * (half - 1 + double(k) / q);  // -pi/2 .. pi/2
      const double sz = half ? 1.0 : -1.0;
      const double ct = (k == 0 && half == 0) || (k == q && half == 1) ? 0.0 : std::cos(theta);
      glm::dvec3 unit(ct * std::cos(phi), ct * std::sin(phi), std::sin(theta));
      if (step == 0 && quadrant % 2 == 1) unit.x = 0.0;  // exact axes: seams weld exactly
      if (step == 0 && quadrant % 2 == 0) unit.y = 0.0;
      if (step == q && quadrant % 2 == 0) unit.x = 0.0;
      if (step == q && quadrant % 2 == 1) unit.y = 0.0;
      if (k == (half ? 0 : q)) unit.z = 0.0;
      glm::dvec3 pos = unit * p.radius + glm::dvec3(sx * inner.x, sy * inner.y, sz * inner.z);
      ids[size_t(c) * rows + r] = mesh.vertex(pos);
    }
  }
  auto at = [&](int c, int r) { return ids[size_t((c + cols) % cols) * rows + r]; };
  for (int c = 0; c < cols; ++c)
    for (int r = 0; r + 1 < rows; ++r)
      // Longitude grows counter-clockwise about z, latitude upward: (c, r) (c+1, r)
      // (c+1, r+1) (c, r+1) is counter-clockwise seen from outside.
      mesh.quad(at(c, r), at(c + 1, r), at(c + 1, r + 1), at(c, r + 1));
  // Bottom and top faces: the four pole copies.
  uint32_t bottom[4], top[4];
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    bottom[quadrant] = at(quadrant * (q + 1), 0);
    top[quadrant] = at(quadrant * (q + 1), rows - 1);
  }
  mesh.quad(bottom[0], bottom[3], bottom[2], bottom[1]);  // seen from below
  mesh.quad(top[0], top[1], top[2], top[3]);
  return mesh.take();
}

bool torusFit(PrimitiveParams& p, const std::string& changed) {
  if (changed != "majorRadius" || p.minorRadius < p.majorRadius) return false;
  p.minorRadius = largestBelow(p.majorRadius);
  return p.minorRadius > 0.0;
}

ParamProblem coneRelations(const PrimitiveParams& p) {
  if (p.radius > 0.0 || p.topRadius > 0.0) return {};
  return {"radius and top radius are both 0: one end of a cone needs a size",
          {"radius", "topRadius"}};
}

ParamProblem roundedBoxRelations(const PrimitiveParams& p) {
  const double smallest = std::min({p.size.x, p.size.y, p.size.z});
  if (2.0 * p.radius < smallest) return {};
  return {"radius (" + shortNumber(p.radius) + ") must be less than " +
              shortNumber(0.5 * smallest) + ", half the smallest size (" + shortNumber(smallest) +
              "): it rounds every edge",
          {"radius", "size"}};
}

bool roundedBoxFit(PrimitiveParams& p, const std::string& changed) {
  const double smallest = std::min({p.size.x, p.size.y, p.size.z});
  if (changed != "size" || 2.0 * p.radius < smallest) return false;
  p.radius = largestBelow(0.5 * smallest);
  return p.radius > 0.0;
}

// ---- the table ---------------------------------------------------------------------------

PrimitiveParams defaultsWith(void (*set)(PrimitiveParams&)) {
  PrimitiveParams p;
  set(p);
  return p;
}

const PrimitiveParam kSize{"size", "size", nullptr, &PrimitiveParams::size};
const PrimitiveParam kRadius{"radius", "radius", &PrimitiveParams::radius};
const PrimitiveParam kHeight{"height", "height", &PrimitiveParams::height};

PrimitiveHull hullOf(const HullPiece& a) {
  PrimitiveHull h;
  h.pieces[0] = a;
  return h;
}
PrimitiveHull hullOf(const HullPiece& a, const HullPiece& b) {
  PrimitiveHull h;
  h.pieces[0] = a;
  h.pieces[1] = b;
  h.count = 2;
  return h;
}

// How far the hull reaches along direction w (object coordinates, any length): its support
// function, the largest w . x over its points.
double hullReach(const PrimitiveHull& hull, const glm::dvec3& w) {
  double reach = -INFINITY;
  for (int k = 0; k < hull.count; ++k) {
    const HullPiece& p = hull.pieces[k];
    reach =
        std::max(reach, glm::dot(p.centre, w) + glm::dot(p.box, glm::abs(w)) +
                            p.disc * std::sqrt(w.x * w.x + w.y * w.y) + p.ball * glm::length(w));
  }
  return reach;
}

const std::vector<PrimitiveInfo> kPrimitives = {
    {NodeKind::Box,
     "box",
     "box",
     "\u25A0",
     "B",
     "A box of size x by y by z",
     {kSize},
     false,
     PrimitiveParams{},
     [](const PrimitiveParams&) { return 0.0; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, p.size * 0.5});
     },
     nullptr,
     nullptr,
     boxMesh},
    {NodeKind::Sphere,
     "sphere",
     "sphere",
     "\u25CF",
     "S",
     "A sphere of a radius",
     {kRadius},
     true,
     PrimitiveParams{},
     [](const PrimitiveParams& p) { return p.radius; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, {}, 0.0, p.radius});
     },
     nullptr,
     nullptr,
     sphereMesh},
    {NodeKind::Cylinder,
     "cylinder",
     "cylinder",
     "\u25AE",
     "C",
     "A cylinder along z",
     {kRadius, kHeight},
     true,
     PrimitiveParams{},
     [](const PrimitiveParams& p) { return p.radius; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, {0, 0, p.height / 2}, p.radius});
     },
     nullptr,
     nullptr,
     cylinderMesh},
    {NodeKind::Cone,
     "cone",
     "cone",
     "\u25B2",
     "A",
     "A cone or frustum along z: radius at the bottom, top radius (either 0: pointed there)",
     {{"radius", "radius", &PrimitiveParams::radius, nullptr, ParamMinimum::NonNegative},
      {"topRadius", "top radius", &PrimitiveParams::topRadius, nullptr, ParamMinimum::NonNegative},
      kHeight},
     true,
     PrimitiveParams{},
     [](const PrimitiveParams& p) { return std::max(p.radius, p.topRadius); },
     [](const PrimitiveParams& p) {
       return hullOf({{0, 0, -p.height / 2}, {}, p.radius},
                     {{0, 0, p.height / 2}, {}, p.topRadius});
     },
     coneRelations,
     nullptr,
     coneMesh},
    {NodeKind::Torus,
     "torus",
     "torus",
     "\u25CE",
     "O",
     "A ring in the xy plane: major radius to the tube's centre, minor radius of the tube",
     {{"majorRadius", "major radius", &PrimitiveParams::majorRadius},
      {"minorRadius", "minor radius", &PrimitiveParams::minorRadius}},
     true,
     PrimitiveParams{},
     [](const PrimitiveParams& p) { return p.majorRadius + p.minorRadius; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, {}, p.majorRadius, p.minorRadius});
     },
     torusRelations,
     torusFit,
     torusMesh},
    {NodeKind::Capsule,
     "capsule",
     "capsule",
     "\u25AC",
     "P",
     "A cylinder along z with hemispherical ends (total height: height + 2 radius)",
     {kRadius, kHeight},
     true,
     PrimitiveParams{},
     [](const PrimitiveParams& p) { return p.radius; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, {0, 0, p.height / 2}, 0.0, p.radius});
     },
     nullptr,
     nullptr,
     capsuleMesh},
    {NodeKind::RoundedBox,
     "roundedBox",
     "rounded box",
     "\u25A2",
     "R",
     "A box of size x by y by z whose edges and corners are rounded with a radius",
     {kSize, {"radius", "corner radius", &PrimitiveParams::radius}},
     true,
     defaultsWith([](PrimitiveParams& p) { p.radius = 0.1; }),
     [](const PrimitiveParams& p) { return p.radius; },
     [](const PrimitiveParams& p) {
       return hullOf({{}, glm::max(p.size * 0.5 - p.radius, glm::dvec3(0.0)), 0.0, p.radius});
     },
     roundedBoxRelations,
     roundedBoxFit,
     roundedBoxMesh},
};

bool inRange(double value, ParamMinimum minimum) {
  if (!std::isfinite(value)) return false;
  return minimum == ParamMinimum::Positive ? value > 0.0 : value >= 0.0;
}

}  // namespace

const std::vector<PrimitiveInfo>& primitiveTable() {
  return kPrimitives;
}

const PrimitiveInfo* primitiveInfo(NodeKind kind) {
  for (const PrimitiveInfo& info : kPrimitives)
    if (info.kind == kind) return &info;
  return nullptr;
}

int autoSegments(double worldRadius, double maxError) {
  if (!(worldRadius > 0.0) || !(maxError > 0.0)) return 12;
  if (maxError >= worldRadius) return 12;
  double n = kPi / std::acos(1.0 - maxError / worldRadius);
  if (!std::isfinite(n)) return kMaxAutoSegments;
  return std::clamp(int(std::ceil(n)), 12, kMaxAutoSegments);
}

void validatePrimitiveParams(NodeKind kind, const PrimitiveParams& p) {
  const PrimitiveInfo* info = primitiveInfo(kind);
  if (!info) throw Error("internal: this node kind is not a primitive");
  const char* const axes[3] = {"x", "y", "z"};
  for (const PrimitiveParam& param : info->params) {
    const char* rule = param.minimum == ParamMinimum::Positive ? "a finite number greater than 0"
                                                               : "a finite number >= 0";
    if (param.scalar && !inRange(p.*param.scalar, param.minimum))
      throw Error(std::string(param.label) + " must be " + rule);
    if (param.vector)
      for (int a = 0; a < 3; ++a)
        if (!inRange((p.*param.vector)[a], param.minimum))
          throw Error(std::string(param.label) + " " + axes[a] + " must be " + rule);
  }
  if (info->relations) {
    ParamProblem problem = info->relations(p);
    if (!problem.message.empty()) throw Error(problem.message);
  }
  if (p.segments != 0 && (p.segments < 3 || p.segments > kMaxSegments))
    throw Error("segments must be 0 (automatic) or from 3 to " + std::to_string(kMaxSegments));
}

std::vector<FittedParam> fitPrimitiveRelations(NodeKind kind, PrimitiveParams* params,
                                               const std::string& changedKey) {
  const PrimitiveInfo* info = primitiveInfo(kind);
  if (!info || !info->relations || !info->fitRelations) return {};
  if (info->relations(*params).message.empty()) return {};
  PrimitiveParams fitted = *params;
  if (!info->fitRelations(fitted, changedKey) || !info->relations(fitted).message.empty())
    return {};
  std::vector<FittedParam> changed;
  for (const PrimitiveParam& param : info->params)
    if (param.scalar && fitted.*param.scalar != params->*param.scalar)
      changed.push_back({param.label, fitted.*param.scalar});
  *params = fitted;
  return changed;
}

TriangleMesh tessellatePrimitive(NodeKind kind, const PrimitiveParams& p, int segments) {
  validatePrimitiveParams(kind, p);
  return primitiveInfo(kind)->tessellate(p, std::max(3, segments));
}

double primitiveRadius(NodeKind kind, const PrimitiveParams& p) {
  const PrimitiveInfo* info = primitiveInfo(kind);
  return info ? info->radius(p) : 0.0;
}

Bounds primitiveLocalBounds(NodeKind kind, const PrimitiveParams& p) {
  return primitiveWorldBounds(kind, p, glm::dmat4(1.0));
}

Bounds primitiveWorldBounds(NodeKind kind, const PrimitiveParams& p,
                            const glm::dmat4& objectToWorld) {
  Bounds b;
  const PrimitiveInfo* info = primitiveInfo(kind);
  if (!info) return b;
  const PrimitiveHull hull = info->hull(p);
  for (int axis = 0; axis < 3; ++axis) {
    // World coordinate `axis` of object point x is w . x + t: w is the matrix's row.
    const glm::dvec3 w(objectToWorld[0][axis], objectToWorld[1][axis], objectToWorld[2][axis]);
    const double t = objectToWorld[3][axis];
    b.min[axis] = t - hullReach(hull, -w);
    b.max[axis] = t + hullReach(hull, w);
  }
  return b;
}

PrimitiveParams scaledPrimitiveParams(NodeKind kind, const PrimitiveParams& params, double factor) {
  PrimitiveParams p = params;
  if (const PrimitiveInfo* info = primitiveInfo(kind))
    for (const PrimitiveParam& param : info->params) {
      if (param.scalar) p.*param.scalar *= factor;
      if (param.vector) p.*param.vector *= factor;
    }
  return p;
}

}  // namespace strata
