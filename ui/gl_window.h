// The editor's window: GLFW with an OpenGL 4.5 core context, falling back to 3.3 core where 4.5
// is unavailable (older Mesa); GL functions through libepoxy.
//
// Threads: the UI thread (GLFW requires the main thread for window calls).
#pragma once

#include <string>
#include <vector>

#include "ui/pixel_rect.h"

struct GLFWwindow;

namespace strata::ui {

// True when a window can be opened: a display is named (DISPLAY or WAYLAND_DISPLAY) and GLFW
// initialises. Otherwise false, with the reason in *why.
bool displayAvailable(std::string* why);

class GlWindow {
 public:
  // Opens a window of `width` x `height` screen coordinates; an invisible one for off-screen
  // rendering when `visible` is false. Multisampled (4 samples, or STRATA_MSAA; none on software
  // renderers unless STRATA_MSAA asks). With `fitScreen`, a visible window larger than the
  // primary monitor's work area (its frame included) is shrunk to it and placed at its corner:
  // the default 1600 x 1000 on a 1280 x 800 screen hid the inspector and the preview settings
  // off the screen (an artist's test). Throws strata::Error saying why it could not.
  GlWindow(int width, int height, const std::string& title, bool visible, bool fitScreen = false);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  int glMajor() const { return major_; }
  int glMinor() const { return minor_; }
  // "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (...)"
  const std::string& description() const { return description_; }
  void setTitle(const std::string& title);

  // Whether present() shows only the rectangles it is given (partial_present.h; chosen on
  // software rasterisers, where every pixel sent costs): the back buffer is then never swapped
  // and keeps its pixels from frame to frame. Otherwise present() swaps, after which the back
  // buffer's pixels are undefined.
  bool presentsParts() const { return partial_; }
  // Shows the frame drawn at width x height framebuffer pixels: `rects` of the back buffer where
  // presentsParts(), else all of it by a swap. Returns whether the back buffer kept its pixels
  // (false after a swap: the next frame must be drawn whole). Parts are presented only when the
  // frame's size, the window's size now and the size at the last swap agree, since the driver
  // resizes the back buffer only at a swap (a rectangle beyond the old buffer is an X error; a
  // smaller window showed the frame shifted); otherwise the frame is swapped whole. An X error
  // while presenting parts turns them off for good (the frame is then swapped).
  bool present(const std::vector<PixelRect>& rects, int width, int height);
  // Whether the window system lost the window's pixels (an expose) since the last call: the
  // next frame must then present everything.
  bool takeExposed();

 private:
  void createWindow(int width, int height, const std::string& title, bool visible, int samples);

  GLFWwindow* window_ = nullptr;
  int major_ = 0, minor_ = 0;
  std::string description_;
  std::string title_;
  bool partial_ = false;
  bool exposed_ = false;
  int swappedWidth_ = -1, swappedHeight_ = -1;  // the framebuffer's size at the last swap
};

}  // namespace strata::ui
