// An OpenGL context without a window or a display, through EGL: on the GPU's own device
// platform (EGL_EXT_platform_device: NVIDIA's driver, Mesa's GPU drivers) or, failing that,
// Mesa's surfaceless platform (llvmpipe). 4.5 core, else 3.3 core. Rendering goes to
// framebuffer objects (RenderTarget); there is no default framebuffer.
//
// Threads: made current on the constructing thread, which must be the one that renders.
#pragma once

#include <string>

namespace strata::ui {

class HeadlessGl {
 public:
  // Creates the context and makes it current. Throws strata::Error saying what is missing
  // (no libEGL, no platform, no OpenGL API, no context of a usable version).
  HeadlessGl();
  ~HeadlessGl();
  HeadlessGl(const HeadlessGl&) = delete;
  HeadlessGl& operator=(const HeadlessGl&) = delete;

  // "EGL device platform: OpenGL 4.5.0 NVIDIA 580.95.05, NVIDIA H200/PCIe/SSE2"
  const std::string& description() const { return description_; }

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string description_;
};

}  // namespace strata::ui
