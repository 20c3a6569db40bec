// epoxy's GL header first: cuda_gl_interop.h then finds GL declared and includes nothing more.
#include <epoxy/gl.h>

#include <cuda_gl_interop.h>
#include <cuda_runtime.h>

#include "engine/util/error.h"
#include "gpu/interop/gl_splat_buffer.h"
#include "gpu/ldi/splats.cuh"
#include "gpu/util/cuda_check.h"
#include "gpu/util/device_stream.h"

namespace strata {

struct CudaGlSplatBuffer::Device {
  DeviceStream stream;                        // every copy runs here
  cudaEvent_t copied = nullptr;               // recorded after each copy
  cudaGraphicsResource_t resource = nullptr;  // the registered GL buffer, or null

  Device() {
    stream = DeviceStream::create();
    STRATA_CUDA_CHECK(cudaEventCreateWithFlags(&copied, cudaEventDisableTiming));
  }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
  ~Device() {
    unregister();
    if (copied) STRATA_CUDA_LOG(cudaEventDestroy(copied));
  }  // then `stream` goes: synchronized and destroyed, failures logged

  // Makes `reader` (the splats' stream, where they are freed once released) wait for the copy
  // queued on `stream`; where that cannot be queued, waits for the copy here instead.
  void orderAfterCopy(const DeviceStream& reader) noexcept {
    cudaError_t status = cudaEventRecord(copied, stream.get());
    if (status == cudaSuccess) status = cudaStreamWaitEvent(reader.get(), copied, 0);
    if (status == cudaSuccess) return;
    logCudaError(status, "ordering the splats' stream after the CUDA-GL copy", __FILE__, __LINE__);
    STRATA_CUDA_LOG(cudaStreamSynchronize(stream.get()));
  }

  void unregister() noexcept {
    if (!resource) return;
    STRATA_CUDA_LOG(cudaStreamSynchronize(stream.get()));  // no copy into it in flight
    STRATA_CUDA_LOG(cudaGraphicsUnregisterResource(resource));
    resource = nullptr;
  }
};

CudaGlSplatBuffer::CudaGlSplatBuffer() = default;

CudaGlSplatBuffer::~CudaGlSplatBuffer() = default;

void CudaGlSplatBuffer::attach(unsigned int glBuffer) {
  detach();
  if (!device_) device_ = std::make_unique<Device>();
  cudaGraphicsResource_t resource = nullptr;
  const cudaError_t status = cudaGraphicsGLRegisterBuffer(&resource, GLuint(glBuffer),
                                                          cudaGraphicsRegisterFlagsWriteDiscard);
  if (status != cudaSuccess) {
    cudaGetLastError();  // clear it, so that later calls do not report it again
    throw Error(std::string("CUDA cannot register the GL buffer (") + cudaGetErrorString(status) +
                "): the GL context is not on the CUDA device");
  }
  device_->resource = resource;
}

void CudaGlSplatBuffer::detach() {
  if (device_) device_->unregister();
}

bool CudaGlSplatBuffer::canCopy(const SplatResource& splats) {
  return dynamic_cast<const DeviceSplats*>(&splats) != nullptr;
}

void CudaGlSplatBuffer::copy(const SplatResource& splats) {
  if (!device_ || !device_->resource)
    throw Error("internal: CUDA-GL copy without a registered buffer");
  auto* source = dynamic_cast<const DeviceSplats*>(&splats);
  if (!source) throw Error("internal: CUDA-GL copy of splats that are not on the CUDA device");
  Device& d = *device_;
  const cudaStream_t stream = d.stream.get();
  const DeviceBuffer<Splat>& from = source->buffer();
  // Mapping orders the copy after GL's earlier use of the buffer; unmapping orders GL's later
  // use after the copy.
  STRATA_CUDA_CHECK(cudaGraphicsMapResources(1, &d.resource, stream));
  void* target = nullptr;
  size_t size = 0;
  cudaError_t status = cudaGraphicsResourceGetMappedPointer(&target, &size, d.resource);
  if (status == cudaSuccess && size < from.bytes()) {
    STRATA_CUDA_LOG(cudaGraphicsUnmapResources(1, &d.resource, stream));
    throw Error("internal: the GL splat buffer holds " + std::to_string(size) + " bytes, " +
                std::to_string(from.bytes()) + " needed");
  }
  bool queued = false;
  if (status == cudaSuccess && from.size()) {
    status = cudaMemcpyAsync(target, from.data(), from.bytes(), cudaMemcpyDeviceToDevice, stream);
    queued = status == cudaSuccess;
  }
  const cudaError_t unmap = cudaGraphicsUnmapResources(1, &d.resource, stream);
  if (queued) d.orderAfterCopy(source->stream());
  STRATA_CUDA_CHECK(status);
  STRATA_CUDA_CHECK(unmap);
}

}  // namespace strata
