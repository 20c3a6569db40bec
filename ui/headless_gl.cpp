#include "ui/headless_gl.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <vector>

#include "engine/util/error.h"
#include "ui/gl_program.h"

namespace strata::ui {
namespace {

bool hasExtension(EGLDisplay display, const char* name) {
  const char* list = eglQueryString(display, EGL_EXTENSIONS);
  if (!list) return false;
  const std::string all = std::string(" ") + list + " ";
  return all.find(std::string(" ") + name + " ") != std::string::npos;
}

// An initialised display on the first platform that gives one; *platform names it.
EGLDisplay openDisplay(std::string* platform, std::string* why) {
  if (!epoxy_has_egl()) {
    *why = "libEGL is not installed (Debian: libegl1, plus libegl-mesa0 for Mesa)";
    return EGL_NO_DISPLAY;
  }
  if (!hasExtension(EGL_NO_DISPLAY, "EGL_EXT_platform_base")) {
    *why = "EGL has no platform extensions (EGL_EXT_platform_base)";
    return EGL_NO_DISPLAY;
  }
  if (hasExtension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
      hasExtension(EGL_NO_DISPLAY, "EGL_EXT_device_base")) {
    EGLint count = 0;
    EGLDeviceEXT devices[16];
    if (eglQueryDevicesEXT(16, devices, &count) && count > 0) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
          *platform = "EGL device platform";
          return d;
        }
      }
    }
  }
  if (hasExtension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
      *platform = "EGL surfaceless platform";
      return d;
    }
  }
  *why = "no EGL device or surfaceless platform could be initialised";
  return EGL_NO_DISPLAY;
}

}  // namespace

HeadlessGl::HeadlessGl() {
  std::string platform, why;
  EGLDisplay display = openDisplay(&platform, &why);
  if (display == EGL_NO_DISPLAY) throw Error("headless OpenGL: " + why);
  display_ = display;
  auto fail = [&](const std::string& what) {
    eglTerminate(display);
    display_ = nullptr;
    throw Error("headless OpenGL (" + platform + "): " + what);
  };
  if (!hasExtension(display, "EGL_KHR_surfaceless_context"))
    fail("no surfaceless contexts (EGL_KHR_surfaceless_context)");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("EGL offers no desktop OpenGL");
  // Any surface type will do (the context renders to framebuffer objects); the default asks for
  // windows, which a headless platform may not offer.
  EGLConfig config = nullptr;
  EGLint configs = 0;
  for (EGLint surfaceType : {EGL_PBUFFER_BIT, 0}) {
    const EGLint attributes[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                 EGL_NONE};
    if (eglChooseConfig(display, attributes, &config, 1, &configs) && configs > 0) break;
  }
  if (configs < 1) fail("no OpenGL config");
  EGLContext context = EGL_NO_CONTEXT;
  for (auto [major, minor] : {std::pair{4, 5}, std::pair{3, 3}}) {
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 major,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 minor,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
    if (context != EGL_NO_CONTEXT) break;
  }
  if (context == EGL_NO_CONTEXT) fail("no OpenGL 4.5 or 3.3 core context");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    context_ = nullptr;
    fail("cannot make the context current");
  }
  description_ = platform + ": " + describeGlContext();
}

HeadlessGl::~HeadlessGl() {
  if (!display_) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

}  // namespace strata::ui
