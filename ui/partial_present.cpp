#include "ui/partial_present.h"

#include <dlfcn.h>
#include <epoxy/glx.h>

namespace strata::ui {
namespace {

// GLFW's native access (glfw3native.h), found at run time: present in GLFW's X11 builds.
using GetDisplay = Display* (*)();
using GetGlxWindow = GLXWindow (*)(GLFWwindow*);

GetDisplay getDisplay() {
  return reinterpret_cast<GetDisplay>(dlsym(RTLD_DEFAULT, "glfwGetX11Display"));
}
GetGlxWindow getGlxWindow() {
  return reinterpret_cast<GetGlxWindow>(dlsym(RTLD_DEFAULT, "glfwGetGLXWindow"));
}

}  // namespace

bool canPresentParts(GLFWwindow* window) {
  const GetDisplay display = getDisplay();
  const GetGlxWindow glxWindow = getGlxWindow();
  if (!display || !glxWindow) return false;
  Display* x = display();
  if (!x || !glxWindow(window)) return false;  // not X11, or an EGL context
  return epoxy_has_glx_extension(x, DefaultScreen(x), "GLX_MESA_copy_sub_buffer");
}

void presentParts(GLFWwindow* window, const std::vector<PixelRect>& rects) {
  Display* x = getDisplay()();
  const GLXWindow drawable = getGlxWindow()(window);
  for (const PixelRect& r : rects)
    if (!r.empty()) glXCopySubBufferMESA(x, drawable, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
}

}  // namespace strata::ui
