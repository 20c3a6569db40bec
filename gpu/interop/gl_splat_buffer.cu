// epoxy's GL header first: cuda_gl_interop.h then finds GL declared and includes nothing more.
#include <epoxy/gl.h>

#include <cuda_gl_interop.h>
#include <cuda_runtime.h>

#include "engine/util/error.h"
#include "gpu/interop/gl_splat_buffer.h"
#include "gpu/ldi/splats.cuh"
#include "gpu/util/cuda_check.h"

namespace strata {

CudaGlSplatBuffer::~CudaGlSplatBuffer() {
  detach();
}

void CudaGlSplatBuffer::attach(unsigned int glBuffer) {
  detach();
  cudaGraphicsResource_t resource = nullptr;
  const cudaError_t status = cudaGraphicsGLRegisterBuffer(&resource, GLuint(glBuffer),
                                                          cudaGraphicsRegisterFlagsWriteDiscard);
  if (status != cudaSuccess) {
    cudaGetLastError();  // clear it, so that later calls do not report it again
    throw Error(std::string("CUDA cannot register the GL buffer (") + cudaGetErrorString(status) +
                "): the GL context is not on the CUDA device");
  }
  resource_ = resource;
}

void CudaGlSplatBuffer::detach() {
  if (!resource_) return;
  cudaGraphicsUnregisterResource(resource_);
  resource_ = nullptr;
}

bool CudaGlSplatBuffer::canCopy(const SplatResource& splats) {
  return dynamic_cast<const DeviceSplats*>(&splats) != nullptr;
}

void CudaGlSplatBuffer::copy(const SplatResource& splats) {
  if (!resource_) throw Error("internal: CUDA-GL copy without a registered buffer");
  auto* device = dynamic_cast<const DeviceSplats*>(&splats);
  if (!device) throw Error("internal: CUDA-GL copy of splats that are not on the CUDA device");
  STRATA_CUDA_CHECK(cudaGraphicsMapResources(1, &resource_, 0));
  void* target = nullptr;
  size_t size = 0;
  cudaError_t status = cudaGraphicsResourceGetMappedPointer(&target, &size, resource_);
  if (status == cudaSuccess && size < device->splats.bytes()) {
    cudaGraphicsUnmapResources(1, &resource_, 0);
    throw Error("internal: the GL splat buffer holds " + std::to_string(size) + " bytes, " +
                std::to_string(device->splats.bytes()) + " needed");
  }
  if (status == cudaSuccess && device->splats.size())
    status = cudaMemcpyAsync(target, device->splats.data(), device->splats.bytes(),
                             cudaMemcpyDeviceToDevice, 0);
  const cudaError_t unmap = cudaGraphicsUnmapResources(1, &resource_, 0);
  STRATA_CUDA_CHECK(status);
  STRATA_CUDA_CHECK(unmap);
}

}  // namespace strata
