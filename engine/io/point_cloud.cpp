#include "engine/io/point_cloud.h"

#include <array>
#include <vector>

#include "engine/io/mesh_writer_formats.h"
#include "engine/ldi/splats.h"
#include "engine/util/atomic_file.h"

namespace strata {
namespace {

// The records are written as they lie in memory: PLY's binary_little_endian.
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "point clouds are written little-endian");

#pragma pack(push, 1)
struct PlyPoint {
  float x, y, z, nx, ny, nz;
  uint8_t r, g, b;
};
#pragma pack(pop)
static_assert(sizeof(PlyPoint) == 27, "packed PLY vertex");

}  // namespace

uint64_t writePointCloudPly(const Ldi& ldi, const std::string& path,
                            const std::function<glm::vec3(uint32_t leafId)>& leafColor) {
  std::vector<PlyPoint> points;
  for (const Splat& s : buildSplats(ldi)) {
    float n[3];
    decodeNormal(s.normal, n);
    const std::array<uint8_t, 3> c = meshio::srgb8(leafColor(splatLeaf(s)));
    points.push_back(
        PlyPoint{s.position[0], s.position[1], s.position[2], n[0], n[1], n[2], c[0], c[1], c[2]});
  }
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
