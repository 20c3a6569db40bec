// Mouse input between the window system and ImGui, frame by frame, so that nothing is lost when
// frames are slow. Dear ImGui 1.86 (Debian's) samples the mouse once a frame: two clicks, or a
// press and release somewhere else, that arrive between two frames become one click at the
// wrong place, and a double-click made during a 300 ms frame is never seen as one.
//
// The queue keeps every button and cursor event with its time. A frame takes the moves in order
// up to the next button change, or that one change alone (as ImGui 1.87's "input trickling"
// does, one step further): a click made during a slow frame is a press in one frame and a
// release in the next, at the cursor position it had when it happened, and a drag pressed,
// moved and released within one slow frame is a press, a frame of moves with the button down,
// and a release. Double-clicks are recognised from the events' own times and positions, not
// from frame times.
//
// Threads: the UI thread (GLFW callbacks run inside glfwPollEvents there). No GL, no ImGui: the
// editor copies what a frame takes into ImGui's IO.
#pragma once

#include <deque>
#include <limits>

namespace strata::ui {

class InputQueue {
 public:
  static constexpr int kButtons = 5;
  static constexpr double kDoubleClickSeconds = 0.35;
  static constexpr double kDoubleClickPixels = 6.0;

  void cursor(double x, double y, double time);
  void button(int button, bool pressed, double time);

  // What one frame sees: the mouse state after the events it took.
  struct Frame {
    double x = 0.0, y = 0.0;
    bool down[kButtons] = {};
    bool doubleClicked[kButtons] = {};  // a press taken this frame completed a double-click
  };
  // Takes this frame's events (see above) and returns the state after them.
  Frame takeFrame();
  // Events not taken yet (a frame takes at most one button change).
  bool pending() const { return !events_.empty(); }
  // The time of the first button change among them (+infinity: none): keys made after it wait
  // until a frame has taken it (editor.cpp).
  double firstButtonTime() const {
    for (const Event& e : events_)
      if (e.kind != Event::Move) return e.time;
    return std::numeric_limits<double>::infinity();
  }

 private:
  struct Event {
    enum Kind { Move, Press, Release } kind = Move;
    int button = 0;
    double x = 0.0, y = 0.0, time = 0.0;
  };
  std::deque<Event> events_;
  double x_ = 0.0, y_ = 0.0;
  bool down_[kButtons] = {};
  // The last press of each button: where and when, for double-clicks.
  double lastPressTime_[kButtons] = {-1e9, -1e9, -1e9, -1e9, -1e9};
  double lastPressX_[kButtons] = {}, lastPressY_[kButtons] = {};
};

}  // namespace strata::ui
