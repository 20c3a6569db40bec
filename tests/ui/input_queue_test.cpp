// The mouse queue (ui/input_queue.h): clicks, drags and double-clicks made while frames are slow
// reach ImGui one change per frame, at the positions and with the timing they had.
#include <gtest/gtest.h>

#include "ui/input_queue.h"

namespace strata::ui {
namespace {

TEST(InputQueue, TwoClicksInOneSlowFrameAreTwoClicksAtTheirPlaces) {
  InputQueue q;
  // During one 500 ms frame: a click at (10, 10), then one at (200, 50).
  q.cursor(10, 10, 0.00);
  q.button(0, true, 0.01);
  q.button(0, false, 0.02);
  q.cursor(200, 50, 0.20);
  q.button(0, true, 0.30);
  q.button(0, false, 0.31);
  std::vector<std::pair<bool, double>> seen;  // (down, x) per frame
  while (q.pending()) {
    const InputQueue::Frame f = q.takeFrame();
    seen.emplace_back(f.down[0], f.x);
    EXPECT_FALSE(f.doubleClicked[0]) << "200 px apart: not a double-click";
  }
  ASSERT_EQ(seen.size(), 6u);
  EXPECT_EQ(seen[0], std::make_pair(false, 10.0));   // the move to the first place
  EXPECT_EQ(seen[1], std::make_pair(true, 10.0));    // the press there
  EXPECT_EQ(seen[2], std::make_pair(false, 10.0));   // its release, there
  EXPECT_EQ(seen[3], std::make_pair(false, 200.0));  // the move
  EXPECT_EQ(seen[4], std::make_pair(true, 200.0));   // the second press, at the second place
  EXPECT_EQ(seen[5], std::make_pair(false, 200.0));
}

TEST(InputQueue, ADoubleClickDuringASlowFrameIsADoubleClick) {
  InputQueue q;
  q.cursor(40, 40, 0.0);
  q.button(0, true, 0.10);
  q.button(0, false, 0.15);
  q.button(0, true, 0.25);
  q.button(0, false, 0.30);
  int doubles = 0, presses = 0;
  bool wasDown = false;
  while (q.pending()) {
    const InputQueue::Frame f = q.takeFrame();
    if (f.down[0] && !wasDown) ++presses;
    if (f.doubleClicked[0]) ++doubles;
    wasDown = f.down[0];
  }
  EXPECT_EQ(presses, 2);
  EXPECT_EQ(doubles, 1);
  // Slow clicks are two single clicks.
  q.button(0, true, 1.0);
  q.takeFrame();
  q.button(0, false, 1.1);
  q.takeFrame();
  q.button(0, true, 2.0);
  EXPECT_FALSE(q.takeFrame().doubleClicked[0]);
}

TEST(InputQueue, ADragWithinOneSlowFrameIsPressMovesRelease) {
  InputQueue q;
  for (int i = 0; i < 100; ++i) q.cursor(i, i, 0.001 * i);  // moves collapse into one
  InputQueue::Frame f = q.takeFrame();
  EXPECT_EQ(f.x, 99.0);
  EXPECT_FALSE(q.pending());
  // Pressed at (5, 5), dragged to (50, 5), released: three frames, the middle one with the
  // button down at the end of the drag (what a drag needs to be seen as one).
  q.cursor(5, 5, 2.0);
  q.button(0, true, 2.01);
  q.cursor(30, 5, 2.05);
  q.cursor(50, 5, 2.1);
  q.button(0, false, 2.2);
  f = q.takeFrame();  // the move to the press point
  EXPECT_EQ(f.x, 5.0);
  EXPECT_FALSE(f.down[0]);
  f = q.takeFrame();
  EXPECT_TRUE(f.down[0]);
  EXPECT_EQ(f.x, 5.0);
  f = q.takeFrame();
  EXPECT_TRUE(f.down[0]);
  EXPECT_EQ(f.x, 50.0);
  f = q.takeFrame();
  EXPECT_FALSE(f.down[0]);
  EXPECT_FALSE(q.pending());
  // Two buttons change in consecutive frames.
  q.button(0, true, 3.0);
  q.button(2, true, 3.0);
  EXPECT_TRUE(q.takeFrame().down[0]);
  f = q.takeFrame();
  EXPECT_TRUE(f.down[0] && f.down[2]);
}

}  // namespace
}  // namespace strata::ui
