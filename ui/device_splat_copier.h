// How splats that a backend keeps in device memory reach the viewport's GL buffer without a trip
// through the host (CUDA-GL interop). ui/ only declares the interface: app/ implements it over
// gpu/ (app/cuda_gl_splat_copier.cpp) and hands it to the editor in EditorOptions. Without one,
// or when attach() fails (GL on Mesa, or on another GPU), the editor takes the host upload path
// and says so in the status bar.
//
// Threads: the UI thread, with the GL context current.
#pragma once

#include <epoxy/gl.h>

#include <string>

#include "engine/ldi/splats.h"

namespace strata::ui {

class DeviceSplatCopier {
 public:
  virtual ~DeviceSplatCopier() = default;
  // "CUDA-GL interop"
  virtual std::string name() const = 0;
  // Registers GL buffer object `buffer` (storage allocated) as the copy target, replacing any
  // earlier one. Throws strata::Error saying why when it cannot.
  virtual void attach(GLuint buffer) = 0;
  // Forgets the target; call before the buffer's storage is reallocated.
  virtual void detach() = 0;
  // Whether `splats` live where this copier can read them (device memory of its device).
  virtual bool accepts(const SplatResource& splats) const = 0;
  // Copies `splats` to the start of the attached buffer, which must hold splats.bytes(); GL
  // commands issued afterwards see them. Throws strata::Error on failure.
  virtual void copy(const SplatResource& splats) = 0;
};

}  // namespace strata::ui
