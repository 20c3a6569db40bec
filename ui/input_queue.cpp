#include "ui/input_queue.h"

#include <cmath>

namespace strata::ui {

void InputQueue::cursor(double x, double y, double time) {
  // Consecutive moves collapse into the last one: only the position matters.
  if (!events_.empty() && events_.back().kind == Event::Move) {
    events_.back().x = x;
    events_.back().y = y;
    events_.back().time = time;
    return;
  }
  Event e;
  e.kind = Event::Move;
  e.x = x;
  e.y = y;
  e.time = time;
  events_.push_back(e);
}

void InputQueue::button(int button, bool pressed, double time) {
  if (button < 0 || button >= kButtons) return;
  Event e;
  e.kind = pressed ? Event::Press : Event::Release;
  e.button = button;
  // At the cursor position of the latest event (what the user pointed at when clicking).
  e.x = events_.empty() ? x_ : events_.back().x;
  e.y = events_.empty() ? y_ : events_.back().y;
  e.time = time;
  events_.push_back(e);
}

InputQueue::Frame InputQueue::takeFrame() {
  Frame frame;
  bool tookAny = false;
  while (!events_.empty()) {
    const Event& e = events_.front();
    if (e.kind != Event::Move) {
      // A button change opens its own frame: what came before it (moves of a drag) is seen
      // with the button as it was, and what follows is the next frame's.
      if (tookAny) break;
      down_[e.button] = e.kind == Event::Press;
      if (e.kind == Event::Press) {
        const double dx = e.x - lastPressX_[e.button], dy = e.y - lastPressY_[e.button];
        if (e.time - lastPressTime_[e.button] <= kDoubleClickSeconds &&
            std::sqrt(dx * dx + dy * dy) <= kDoubleClickPixels) {
          frame.doubleClicked[e.button] = true;
          lastPressTime_[e.button] = -1e9;  // a third click starts a new pair
        } else {
          lastPressTime_[e.button] = e.time;
        }
        lastPressX_[e.button] = e.x;
        lastPressY_[e.button] = e.y;
      }
    }
    x_ = e.x;
    y_ = e.y;
    const bool buttonChange = e.kind != Event::Move;
    events_.pop_front();
    tookAny = true;
    if (buttonChange) break;
  }
  frame.x = x_;
  frame.y = y_;
  for (int b = 0; b < kButtons; ++b) frame.down[b] = down_[b];
  return frame;
}

}  // namespace strata::ui
