#include "ui/surfel_splats.h"

#include <glm/geometric.hpp>

#include <cmath>

#include "engine/io/point_cloud.h"

namespace strata::ui {

std::vector<Splat> buildSplats(const Ldi& ldi) {
  std::vector<Splat> splats;
  splats.reserve(ldi.surfelCount() / 3 + 16);
  forEachDominantSurfel(ldi, [&](int axis, const Surfel& s, const float*, const glm::dvec3& p) {
    splats.push_back(Splat{
        {float(p.x), float(p.y), float(p.z)}, s.normal, (surfelLeaf(s.tag) << 2) | uint32_t(axis)});
  });
  return splats;
}

bool pickSplat(const std::vector<Splat>& splats, const Ray& ray, double radius, SplatHit* hit) {
  bool found = false;
  double best = 1e300;
  const double r2 = radius * radius;
  for (const Splat& s : splats) {
    glm::dvec3 p(s.position[0], s.position[1], s.position[2]);
    glm::dvec3 d = p - ray.origin;
    double t = glm::dot(d, ray.direction);
    if (t <= 0.0 || t >= best) continue;
    glm::dvec3 off = d - t * ray.direction;
    if (glm::dot(off, off) > r2) continue;
    float n[3];
    decodeNormal(s.normal, n);
    if (n[0] * ray.direction.x + n[1] * ray.direction.y + n[2] * ray.direction.z > 0.0) continue;
    best = t;
    found = true;
    hit->leaf = splatLeaf(s);
    hit->position = p;
    hit->distance = t;
  }
  return found;
}

}  // namespace strata::ui
