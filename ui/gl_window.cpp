#include "ui/gl_window.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>

#include "engine/util/error.h"
#include "ui/gl_program.h"
#include "ui/partial_present.h"

namespace strata::ui {
namespace {

std::mutex g_errorMutex;
std::string g_lastGlfwError;

void onGlfwError(int code, const char* description) {
  std::lock_guard<std::mutex> lock(g_errorMutex);
  g_lastGlfwError = "GLFW error " + std::to_string(code) + ": " + (description ? description : "");
}

std::string lastGlfwError() {
  std::lock_guard<std::mutex> lock(g_errorMutex);
  return g_lastGlfwError.empty() ? "no details from GLFW" : g_lastGlfwError;
}

// glfwInit is reference-counted here so that several windows (tests) can come and go.
int g_glfwUsers = 0;

bool acquireGlfw(std::string* why) {
  if (g_glfwUsers == 0) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) {
      if (why) *why = "GLFW could not initialise (" + lastGlfwError() + ")";
      return false;
    }
  }
  ++g_glfwUsers;
  return true;
}

void releaseGlfw() {
  if (--g_glfwUsers == 0) glfwTerminate();
}

bool displayNamed() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

// Multisampling of the window: STRATA_MSAA samples (0 turns it off), 4 by default.
int multisamples() {
  const char* v = std::getenv("STRATA_MSAA");
  if (!v || !*v) return 4;
  int n = std::atoi(v);
  return n < 0 ? 0 : n > 16 ? 16 : n;
}

}  // namespace

bool displayAvailable(std::string* why) {
  if (!displayNamed()) {
    if (why) *why = "no display (neither DISPLAY nor WAYLAND_DISPLAY is set)";
    return false;
  }
  if (!acquireGlfw(why)) return false;
  releaseGlfw();
  return true;
}

GlWindow::GlWindow(int width, int height, const std::string& title, bool visible, bool fitScreen) {
  if (!displayNamed())
    throw Error("cannot open a window: no display (neither DISPLAY nor WAYLAND_DISPLAY is set)");
  std::string why;
  if (!acquireGlfw(&why)) throw Error("cannot open a window: " + why);
  int workX = 0, workY = 0, workWidth = 0, workHeight = 0;
  GLFWmonitor* monitor = fitScreen && visible ? glfwGetPrimaryMonitor() : nullptr;
  if (monitor) glfwGetMonitorWorkarea(monitor, &workX, &workY, &workWidth, &workHeight);
  const bool fits = workWidth <= 0 || workHeight <= 0 ||
                    (width <= workWidth && height <= workHeight);  // unknown: as asked
  if (!fits) {
    width = std::min(width, workWidth);
    height = std::min(height, workHeight);
  }
  int samples = multisamples();
  bool software = false;
  for (int attempt = 0; attempt < 2; ++attempt) {
    createWindow(width, height, title, visible, samples);
    if (!window_) {
      std::string error = lastGlfwError();
      releaseGlfw();
      throw Error("cannot create a window with an OpenGL 4.5 or 3.3 core context (" + error + ")");
    }
    glfwMakeContextCurrent(window_);
    description_ = describeGlContext();
    // Software rasterisers pay for every sample (a frame takes twice as long with 4): open the
    // window again single-sampled there, unless STRATA_MSAA asks for samples.
    software = description_.find("llvmpipe") != std::string::npos ||
               description_.find("softpipe") != std::string::npos;
    if (!software || samples == 0 || std::getenv("STRATA_MSAA")) break;
    glfwDestroyWindow(window_);
    window_ = nullptr;
    samples = 0;
  }
  // Partial presents where pixels cost (software rasterisers); STRATA_PARTIAL_PRESENT=0 turns
  // them off, =1 asks for them on any driver that offers them.
  const char* partial = std::getenv("STRATA_PARTIAL_PRESENT");
  const bool wanted = partial && *partial ? std::atoi(partial) != 0 : software;
  // Not on a multisampled window: the driver resolves its samples only at a swap.
  partial_ = wanted && samples == 0 && canPresentParts(window_);
  if (!fits) {
    // Its frame (a title bar) inside the work area as well; none without a window manager.
    int left = 0, top = 0, right = 0, bottom = 0;
    glfwGetWindowFrameSize(window_, &left, &top, &right, &bottom);
    const int w = std::max(320, width - left - right), h = std::max(240, height - top - bottom);
    if (w != width || h != height) glfwSetWindowSize(window_, w, h);
    glfwSetWindowPos(window_, workX + left, workY + top);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) {
    static_cast<GlWindow*>(glfwGetWindowUserPointer(w))->exposed_ = true;
  });
  // No vertical sync: a swap must not wait up to a refresh (16.7 ms at 60 Hz) before an edit's
  // result shows. The editor draws only while there is input or work (Editor::frame sleeps in
  // glfwWaitEvents otherwise), so frames are not drawn for nothing.
  glfwSwapInterval(0);
  description_ +=
      samples > 0 ? ", " + std::to_string(samples) + "x multisampling" : ", no multisampling";
  if (partial_) description_ += ", partial presents";
}

void GlWindow::createWindow(int width, int height, const std::string& title, bool visible,
                            int samples) {
  const int versions[][2] = {{4, 5}, {3, 3}};
  for (const auto& v : versions) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, v[0]);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, v[1]);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SAMPLES, samples);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (window_) {
      major_ = v[0];
      minor_ = v[1];
      return;
    }
  }
}

GlWindow::~GlWindow() {
  if (window_) glfwDestroyWindow(window_);
  releaseGlfw();
}

bool GlWindow::present(const std::vector<PixelRect>& rects, int width, int height) {
  int nowWidth = 0, nowHeight = 0;
  glfwGetFramebufferSize(window_, &nowWidth, &nowHeight);
  const bool sameSize = width == swappedWidth_ && height == swappedHeight_ && nowWidth == width &&
                        nowHeight == height;
  if (partial_ && sameSize) {
    if (presentParts(window_, rects)) return true;
    partial_ = false;  // the X server refused: swap from now on
    description_ += " (turned off after an X error)";
  }
  width = nowWidth;
  height = nowHeight;
  glfwSwapBuffers(window_);
  swappedWidth_ = width;
  swappedHeight_ = height;
  return false;
}

bool GlWindow::takeExposed() {
  const bool exposed = exposed_;
  exposed_ = false;
  return exposed;
}

void GlWindow::setTitle(const std::string& title) {
  if (title == title_) return;  // called every frame; X11 round trip only on a change
  title_ = title;
  glfwSetWindowTitle(window_, title.c_str());
}

}  // namespace strata::ui
