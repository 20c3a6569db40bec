#include "engine/eval/cpu_backend.h"

#include "engine/ldi/combine_ldi.h"
#include "engine/ldi/offset_ldi.h"
#include "engine/ldi/offset_math.h"
#include "engine/ldi/sample_mesh.h"
#include "engine/util/error.h"
#include "engine/util/memory.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace {
class CpuLdi : public LdiResource {
 public:
  explicit CpuLdi(std::shared_ptr<const Ldi> ldi) : ldi_(std::move(ldi)) {}
  const Grid& grid() const override { return ldi_->grid; }
  size_t surfelCount() const override { return ldi_->surfelCount(); }
  size_t bytes() const override { return ldi_->bytes(); }
  const std::shared_ptr<const Ldi>& ldi() const { return ldi_; }

 private:
  std::shared_ptr<const Ldi> ldi_;
};

const std::shared_ptr<const Ldi>& hostLdi(const LdiHandle& handle) {
  auto* cpu = dynamic_cast<const CpuLdi*>(handle.get());
  if (!cpu) throw Error("internal: an LDI of another backend was passed to the CPU backend");
  return cpu->ldi();
}
}  // namespace

std::string CpuBackend::description() const {
  int n = workerCount();
  return "cpu (" + std::to_string(n) + (n == 1 ? " thread)" : " threads)");
}

LdiHandle CpuBackend::sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld,
                                 const Grid& grid, uint32_t leafId, Progress& progress) {
  return std::make_shared<CpuLdi>(strata::sampleMesh(mesh, objectToWorld, grid, leafId, &progress));
}

LdiHandle CpuBackend::combine(RayOp op, const std::vector<LdiHandle>& children, const Grid& grid,
                              Progress& progress) {
  std::vector<std::shared_ptr<const Ldi>> inputs;
  inputs.reserve(children.size());
  for (const auto& c : children) inputs.push_back(hostLdi(c));
  return std::make_shared<CpuLdi>(combineLdis(op, inputs, grid, &progress));
}

LdiHandle CpuBackend::offset(const LdiHandle& ldi, double distance, Progress& progress) {
  return std::make_shared<CpuLdi>(offsetLdi(*wholeLdi(hostLdi(ldi)), distance, &progress));
}

LdiHandle Backend::offset(const LdiHandle&, double, Progress&) {
  throw Error("the " + description() +
              " backend cannot evaluate offset, shell, round and fillet nodes: run with "
              "--backend cpu");
}

LdiHandle Backend::rewindow(const LdiHandle&, const Grid&) {
  return nullptr;
}

LdiHandle Backend::modify(Modifier modifier, double amount, const LdiHandle& ldi,
                          Progress& progress, const LdiHandle& wallOf) {
  // Progress "modify" over the whole modifier: a round's or fillet's two offsets each half of it
  // (an offset reports "offset" over its own passes).
  const auto part = [&progress](double from, double to) {
    return Progress(&progress, [&progress, from, to](const std::string&, double f) {
      progress.report("modify", from + (to - from) * f);
    });
  };
  switch (modifier) {
    case Modifier::Offset: {
      Progress whole = part(0.0, 1.0);
      return offset(ldi, amount, whole);
    }
    case Modifier::Shell: {  // the solid minus its inward offset (or that of wallOf)
      Progress whole = part(0.0, 1.0);
      return combine(RayOp::Difference, {ldi, offset(wallOf ? wallOf : ldi, -amount, whole)},
                     ldi->grid(), progress);
    }
    case Modifier::Round: {  // opening
      Progress first = part(0.0, 0.5), second = part(0.5, 1.0);
      return offset(offset(ldi, -amount, first), amount, second);
    }
    case Modifier::Fillet: {  // closing
      Progress first = part(0.0, 0.5), second = part(0.5, 1.0);
      return offset(offset(ldi, amount, first), -amount, second);
    }
    case Modifier::None:
      break;
  }
  return ldi;
}

LdiHandle CpuBackend::crop(const LdiHandle& ldi, const Grid& window, Progress& progress) {
  progress.check();
  return std::make_shared<CpuLdi>(cropLdi(hostLdi(ldi), window));
}

LdiHandle CpuBackend::rewindow(const LdiHandle& ldi, const Grid& window) {
  return std::make_shared<CpuLdi>(rewindowLdi(hostLdi(ldi), window));
}

LdiHandle CpuBackend::empty(const Grid& grid) {
  return std::make_shared<CpuLdi>(makeEmptyLdi(grid));
}

LdiMeasure CpuBackend::measure(const LdiHandle& ldi, Progress& progress) {
  progress.check();
  return measureLdi(*hostLdi(ldi));
}

std::shared_ptr<const Ldi> CpuBackend::download(const LdiHandle& ldi) {
  return wholeLdi(hostLdi(ldi));
}

SplatsHandle Backend::splats(const LdiHandle& ldi, Progress& progress) {
  progress.check();
  std::shared_ptr<const Ldi> host = download(ldi);
  SplatLevels levels;
  std::vector<Splat> splats = buildSplats(*host, &levels);
  return std::make_shared<HostSplats>(std::move(splats), levels);
}

std::vector<LdiHandle> Backend::sampleMeshes(const std::vector<LeafToSample>& leaves,
                                             const Grid& grid, Progress& progress) {
  std::vector<LdiHandle> out;
  out.reserve(leaves.size());
  for (const LeafToSample& leaf : leaves)
    out.push_back(sampleMesh(*leaf.mesh, leaf.objectToWorld, grid, leaf.leafId, progress));
  return out;
}

uint64_t Backend::offsetBytesPerNode() const {
  return kHostOffsetBytesPerNode;
}

uint64_t Backend::memoryAvailable() const {
  return availableMemoryBytes();
}

TileContour Backend::contourTile(const LdiHandle& root, const glm::ivec3& globalCells,
                                 const glm::ivec3& begin, const glm::ivec3& end,
                                 Progress& progress) {
  std::shared_ptr<const Ldi> ldi = download(root);
  return strata::contourTile(*ldi, globalCells, begin, end, &progress, &hostContourArrays_);
}

}  // namespace strata
