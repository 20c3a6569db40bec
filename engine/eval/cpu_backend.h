// The CPU backend: LDIs in host memory, computed on all worker threads. The reference that the
// CUDA backend is tested against.
#pragma once

#include "engine/eval/backend.h"

namespace strata {

class CpuBackend : public Backend {
 public:
  std::string description() const override;
  LdiHandle sampleMesh(const TriangleMesh& mesh, const glm::dmat4& objectToWorld, const Grid& grid,
                       uint32_t leafId, Progress& progress) override;
  LdiHandle combine(RayOp op, const std::vector<LdiHandle>& children, const Grid& grid,
                    Progress& progress) override;
  LdiHandle empty(const Grid& grid) override;
  LdiHandle crop(const LdiHandle& ldi, const Grid& window, Progress& progress) override;
  LdiHandle rewindow(const LdiHandle& ldi, const Grid& window) override;
  LdiHandle offset(const LdiHandle& ldi, double distance, Progress& progress) override;
  bool evaluatesModifiers() const override { return true; }
  LdiMeasure measure(const LdiHandle& ldi, Progress& progress) override;
  std::shared_ptr<const Ldi> download(const LdiHandle& ldi) override;
};

}  // namespace strata
