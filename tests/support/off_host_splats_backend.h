// A CPU backend whose splats are not in host memory (hostData() null), as the CUDA backend's
// are: whoever needs them on the host copies them (copyToHost), as the preview worker does for
// an editor without CUDA-GL interop. For tests of that path where there is no GPU.
//
// Threads: as CpuBackend.
#pragma once

#include <memory>

#include "engine/eval/cpu_backend.h"
#include "engine/ldi/splats.h"

namespace strata::test {

// The CPU backend's splats behind an interface that keeps them off the host.
class OffHostSplats : public SplatResource {
 public:
  explicit OffHostSplats(SplatsHandle inner) : inner_(std::move(inner)) {}
  size_t count() const override { return inner_->count(); }
  SplatLevels levels() const override { return inner_->levels(); }
  const Splat* hostData() const override { return nullptr; }
  void copyToHost(Splat* out) const override { inner_->copyToHost(out); }

 private:
  SplatsHandle inner_;
};

class OffHostSplatsBackend : public CpuBackend {
 public:
  SplatsHandle splats(const LdiHandle& ldi, Progress& progress) override {
    return std::make_shared<OffHostSplats>(CpuBackend::splats(ldi, progress));
  }
};

}  // namespace strata::test
