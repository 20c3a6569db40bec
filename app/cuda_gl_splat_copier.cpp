#include "app/cuda_gl_splat_copier.h"

#if defined(STRATA_HAS_EDITOR)

#if defined(STRATA_HAS_CUDA_GL)
#include "gpu/interop/gl_splat_buffer.h"
#endif

namespace strata {

#if defined(STRATA_HAS_CUDA_GL)
namespace {

class CudaGlSplatCopier : public ui::DeviceSplatCopier {
 public:
  std::string name() const override { return "CUDA-GL interop"; }
  void attach(GLuint buffer) override { buffer_.attach(buffer); }
  void detach() override { buffer_.detach(); }
  bool accepts(const SplatResource& splats) const override {
    return CudaGlSplatBuffer::canCopy(splats);
  }
  void copy(const SplatResource& splats) override { buffer_.copy(splats); }

 private:
  CudaGlSplatBuffer buffer_;
};

}  // namespace

std::unique_ptr<ui::DeviceSplatCopier> makeCudaGlSplatCopier() {
  return std::make_unique<CudaGlSplatCopier>();
}
#else
std::unique_ptr<ui::DeviceSplatCopier> makeCudaGlSplatCopier() {
  return nullptr;
}
#endif

}  // namespace strata

#endif
