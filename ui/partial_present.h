// Showing rectangles of a window's back buffer without a swap (GLX_MESA_copy_sub_buffer: Mesa
// on X11). A window presented this way is never swapped, so its back buffer keeps its pixels
// from frame to frame and a frame redraws and sends only what changed (window_redraw.h).
//
// Threads: the UI thread, with the window's context current.
#pragma once

#include <vector>

#include "ui/pixel_rect.h"

struct GLFWwindow;

namespace strata::ui {

// Whether `window` can present rectangles of its back buffer: an X11 window with a GLX context
// whose display offers GLX_MESA_copy_sub_buffer (GLFW's native X11 access is looked up at run
// time, so a GLFW built for Wayland only answers false).
bool canPresentParts(GLFWwindow* window);

// Copies `rects` (framebuffer pixels) of the back buffer to the window on the screen and waits
// for the X server's answer. Returns false when it reported an error (trapped: Xlib's default
// handler would end the process); the window then shows what it showed before.
bool presentParts(GLFWwindow* window, const std::vector<PixelRect>& rects);

}  // namespace strata::ui
