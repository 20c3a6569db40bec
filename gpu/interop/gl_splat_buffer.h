// CUDA-GL interop for the editor's splats, CUDA side: copies the CUDA backend's splats
// (DeviceSplats, gpu/ldi/splats.cuh) into an OpenGL buffer object, device to device, with no
// trip through the host. Plain C++: no GL or CUDA header needed to include it; GL buffer
// objects are passed by name (a GLuint).
//
// Threads: the thread that has the GL context current (the editor's UI thread). The GL context
// must run on the CUDA device the splats live on; on any other GL (Mesa's llvmpipe, another
// GPU) attach() throws, and the caller takes the host upload path instead.
//
// Streams: copies run on a stream this object owns (not the backend's, which may be busy with
// the next evaluation, nor the legacy stream 0). GL work issued after copy() returns sees the
// copied splats (cudaGraphicsUnmapResources on that stream orders it), and the splats' own
// stream is made to wait for the copy, so their stream-ordered free cannot overtake it.
#pragma once

#include <cstddef>
#include <memory>

#include "engine/ldi/splats.h"

namespace strata {

class CudaGlSplatBuffer {
 public:
  CudaGlSplatBuffer();   // touches no device: the stream is made by the first attach()
  ~CudaGlSplatBuffer();  // detaches; failures at teardown are logged to stderr
  CudaGlSplatBuffer(const CudaGlSplatBuffer&) = delete;
  CudaGlSplatBuffer& operator=(const CudaGlSplatBuffer&) = delete;

  // Registers GL buffer object `glBuffer` (with storage already allocated) for writing by
  // CUDA. Detach before the buffer's storage is reallocated (glBufferData) and attach again
  // after. Throws strata::Error quoting CUDA's reason when the buffer cannot be registered.
  void attach(unsigned int glBuffer);
  // Waits for copies in flight, then unregisters the buffer (a failure is logged, not thrown).
  void detach();

  // Copies all of `splats` to the start of the attached buffer (see Streams above). Throws
  // strata::Error when the splats are not the CUDA backend's, or when they do not fit in the
  // mapped buffer.
  void copy(const SplatResource& splats);
  // Whether `splats` are the CUDA backend's (device-resident), i.e. what copy() takes.
  static bool canCopy(const SplatResource& splats);

 private:
  struct Device;  // the registered buffer, the copy stream and its event (gl_splat_buffer.cu)
  std::unique_ptr<Device> device_;
};

}  // namespace strata
