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

// Xlib's, found the same way (loaded by GLFW's X11 build; not a link dependency of ours).
using Sync = int (*)(Display*, Bool);
using SetErrorHandler = XErrorHandler (*)(XErrorHandler);

bool g_failed = false;

int onXError(Display*, XErrorEvent*) {
  g_failed = true;
  return 0;
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

bool presentParts(GLFWwindow* window, const std::vector<PixelRect>& rects) {
  static const GetDisplay display = getDisplay();
  static const GetGlxWindow glxWindow = getGlxWindow();
  static const auto sync = reinterpret_cast<Sync>(dlsym(RTLD_DEFAULT, "XSync"));
  static const auto setErrorHandler =
      reinterpret_cast<SetErrorHandler>(dlsym(RTLD_DEFAULT, "XSetErrorHandler"));
  if (!display || !glxWindow || !sync || !setErrorHandler) return false;
  Display* x = display();
  const GLXWindow drawable = glxWindow(window);
  // Errors trapped for these requests only (the UI thread is Xlib's only user here).
  sync(x, False);
  g_failed = false;
  const XErrorHandler previous = setErrorHandler(onXError);
  for (const PixelRect& r : rects)
    if (!r.empty()) glXCopySubBufferMESA(x, drawable, r.x0, r.y0, r.x1 - r.x0, r.y1 - r.y0);
  sync(x, False);
  setErrorHandler(previous);
  return !g_failed;
}

}  // namespace strata::ui
