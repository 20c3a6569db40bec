#include "engine/io/point_cloud.h"

#include <cmath>
#include <cstring>
#include <vector>

#include "engine/util/atomic_file.h"

namespace strata {
namespace {

#pragma pack(push, 1)
struct PlyPoint {
  float x, y, z, nx, ny, nz;
  uint8_t r, g, b;
};
#pragma pack(pop)
static_assert(sizeof(PlyPoint) == 27, "packed PLY vertex");

uint8_t toByte(float c) {
  return uint8_t(std::lround(std::fmin(1.f, std::fmax(0.f, c)) * 255.f));
}
}  // namespace

glm::dvec3 surfelPosition(const Grid& grid, int axis, int64_t ray, float depth) {
  const int u = grid.uAxis(axis), v = grid.vAxis(axis);
  const int64_t raysU = grid.raysU(axis);
  glm::dvec3 p;
  p[axis] = grid.origin[axis] + grid.h * double(depth);
  p[u] = grid.origin[u] + grid.h * double(grid.first[u] + ray % raysU);
  p[v] = grid.origin[v] + grid.h * double(grid.first[v] + ray / raysU);
  return p;
}

void forEachDominantSurfel(const Ldi& ldi,
                           const std::function<void(int axis, const Surfel& s, const float n[3],
                                                    const glm::dvec3& p)>& visit) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisLdi& a = ldi.axes[axis];
    for (int64_t ray = 0; ray + 1 < int64_t(a.offsets.size()); ++ray) {
      for (uint32_t k = a.offsets[size_t(ray)]; k < a.offsets[size_t(ray) + 1]; ++k) {
        const Surfel& s = a.surfels[k];
        float n[3];
        decodeNormal(s.normal, n);
        if (onDominantAxis(n, axis))
          visit(axis, s, n, surfelPosition(ldi.grid, axis, ray, s.depth));
      }
    }
  }
}

uint64_t writePointCloudPly(const Ldi& ldi, const std::string& path,
                            const std::function<glm::vec3(uint32_t leafId)>& leafColor) {
  std::vector<PlyPoint> points;
  forEachDominantSurfel(ldi, [&](int, const Surfel& s, const float n[3], const glm::dvec3& p) {
    glm::vec3 c = leafColor(surfelLeaf(s.tag));
    points.push_back(PlyPoint{float(p.x), float(p.y), float(p.z), n[0], n[1], n[2], toByte(c.r),
                              toByte(c.g), toByte(c.b)});
  });
  writeFileAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\ncomment written by strata: LDI surfels\n"
        << "element vertex " << points.size() << "\n"
        << "property float x\nproperty float y\nproperty float z\n"
        << "property float nx\nproperty float ny\nproperty float nz\n"
        << "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    out.write(reinterpret_cast<const char*>(points.data()),
              std::streamsize(points.size() * sizeof(PlyPoint)));
  });
  return points.size();
}

}  // namespace strata
