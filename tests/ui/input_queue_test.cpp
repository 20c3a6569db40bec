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
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0], std::make_pair(true, 10.0));    // press at the first place
  EXPECT_EQ(seen[1], std::make_pair(false, 200.0));  // release, then the move
  EXPECT_EQ(seen[2], std::make_pair(true, 200.0));   // the second press
  EXPECT_EQ(seen[3], std::make_pair(false, 200.0));
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

TEST(InputQueue, ButtonsChangeIndependentlyAndMovesCollapse) {
  InputQueue q;
  q.button(0, true, 0.0);
  q.button(2, true, 0.0);  // another button: the same frame
  for (int i = 0; i < 100; ++i) q.cursor(i, i, 0.001 * i);
  const InputQueue::Frame f = q.takeFrame();
  EXPECT_TRUE(f.down[0]);
  EXPECT_TRUE(f.down[2]);
  EXPECT_EQ(f.x, 99.0);
  EXPECT_FALSE(q.pending());
  // A drag: press, moves, release in one batch: the press frame sees the start position.
  q.button(0, false, 1.0);
  q.takeFrame();
  q.cursor(5, 5, 2.0);
  q.button(0, true, 2.01);
  q.cursor(50, 5, 2.1);
  q.button(0, false, 2.2);
  const InputQueue::Frame press = q.takeFrame();
  EXPECT_TRUE(press.down[0]);
  EXPECT_EQ(press.x, 50.0);  // the moves before the release come with the press
  const InputQueue::Frame release = q.takeFrame();
  EXPECT_FALSE(release.down[0]);
}

}  // namespace
}  // namespace strata::ui
