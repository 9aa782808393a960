// The playback clock (scene/clock.h): the clip time of a frame, the pre-roll's first frame, and
// the limits, each naming its field.
#include "pelage/scene/clock.h"

#include <gtest/gtest.h>

#include <string>

#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

std::string fieldOf(void (*f)()) {
  try {
    f();
  } catch (const InputError& e) {
    return e.field();
  }
  return "(accepted)";
}

TEST(Clock, FrameTimesAreStartPlusFrameOverFps) {
  Clock c;
  EXPECT_EQ(c.secondsAt(0), 0.0);
  EXPECT_EQ(c.secondsAt(30), 1.0);
  c.fps = 24.0;
  c.startSeconds = 0.5;
  EXPECT_EQ(c.secondsAt(0), 0.5);
  EXPECT_EQ(c.secondsAt(12), 1.0);
  EXPECT_EQ(c.secondsAt(7), 0.5 + 7.0 / 24.0);  // the one formula every client uses, bit for bit
}

TEST(Clock, PreRollStartsAtFrameZeroOrThatManyFramesBefore) {
  Clock c;  // -1: from frame 0
  EXPECT_EQ(preRollStart(12, c), 0);
  c.preRollFrames = 2;
  EXPECT_EQ(preRollStart(12, c), 10);
  EXPECT_EQ(preRollStart(1, c), 0);
  c.preRollFrames = 0;
  EXPECT_EQ(preRollStart(12, c), 12);
}

TEST(Clock, LimitsNameTheirFields) {
  EXPECT_EQ(fieldOf([] { validateFramesPerSecond(0.5); }), "fps");
  EXPECT_EQ(fieldOf([] { validateFramesPerSecond(kMaxFramesPerSecond); }), "(accepted)");
  EXPECT_EQ(fieldOf([] { validateFramesPerSecond(kMaxFramesPerSecond * 1.01, "rate"); }), "rate");
  EXPECT_EQ(fieldOf([] { validateStartSeconds(-1.0, "time"); }), "time");
  EXPECT_EQ(fieldOf([] { validateStartSeconds(kMaxStartSeconds); }), "(accepted)");
  EXPECT_EQ(fieldOf([] { validatePreRoll(-1); }), "(accepted)");
  EXPECT_EQ(fieldOf([] { validatePreRoll(-1, "preroll", false); }), "preroll");
  EXPECT_EQ(fieldOf([] { validatePreRoll(kMaxPreRollFrames + 1); }), "preroll");
  EXPECT_EQ(fieldOf([] { validateClock(Clock{}); }), "(accepted)");
  EXPECT_EQ(fieldOf([] { validateClock(Clock{30.0, -0.5, -1}); }), "time");
  EXPECT_EQ(fieldOf([] { validateClock(Clock{30.0, 0.0, -2}); }), "preroll");
  EXPECT_EQ(fieldOf([] { validateClock(Clock{0.0, 0.0, -1}); }), "fps");
  try {
    validateFramesPerSecond(0.5);
    ADD_FAILURE() << "0.5 fps accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "fps 0.5 is out of range [1, 1000]");
  }
}

}  // namespace
}  // namespace pelage::scene
