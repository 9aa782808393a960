// Frame ranges and frame file names (`pelage render` / `pelage export`).
#include "pelage/scene/frame_range.h"

#include <gtest/gtest.h>

#include "pelage/util/error.h"

namespace pelage::scene {
namespace {

TEST(FrameRange, ParsesInclusiveRangesAndSingleFrames) {
  const FrameRange r = parseFrameRange("0:99");
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.last, 99);
  EXPECT_EQ(r.count(), 100);
  const FrameRange one = parseFrameRange("42");
  EXPECT_EQ(one.first, 42);
  EXPECT_EQ(one.count(), 1);
  EXPECT_EQ(parseFrameRange("7:7").count(), 1);
  EXPECT_EQ(parseFrameRange("0:9999999").count(), 10000000);
}

TEST(FrameRange, RejectsBadRangesNamingTheOption) {
  for (const char* bad : {"", ":", "5:", ":5", "a:b", "1:2:0", "1:2:-1", "1:2:3:4", "1:9:", "1.5:3",
                          "-1:4", "9:3", "0:10000000", " 1:2", "1:2 ", "99999999999:1"}) {
    try {
      parseFrameRange(bad, "--frames");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos) << e.what();
    }
  }
}

TEST(FrameRange, StepsKeepEveryStepthFrameAndEndOnTheStep) {
  const FrameRange r = parseFrameRange("0:30:5");
  EXPECT_EQ(r.first, 0);
  EXPECT_EQ(r.last, 30);
  EXPECT_EQ(r.step, 5);
  EXPECT_EQ(r.count(), 7);
  EXPECT_EQ(r.at(6), 30);
  EXPECT_TRUE(r.contains(25));
  EXPECT_FALSE(r.contains(26));
  EXPECT_FALSE(r.contains(35));
  const FrameRange down = parseFrameRange("3:29:5");  // 3, 8, ..., 28: the last rounded down
  EXPECT_EQ(down.last, 28);
  EXPECT_EQ(down.count(), 6);
  EXPECT_EQ(parseFrameRange("4:4:9").count(), 1);
  // A range built in code whose last frame is off the step is refused, naming the field.
  try {
    validateFrameRange(FrameRange{0, 10, 3}, "frames");
    ADD_FAILURE() << "accepted 0:10:3";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not on the step"), std::string::npos) << e.what();
  }
  EXPECT_THROW(validateFrameRange(FrameRange{0, 10, 0}), InputError);
  EXPECT_NO_THROW(validateFrameRange(FrameRange{0, 9, 3}));
}

TEST(FrameRange, FileNamesHaveFiveDigitsAtLeast) {
  EXPECT_EQ(frameFileName(0, ".png"), "frame_00000.png");
  EXPECT_EQ(frameFileName(42, ".glb"), "frame_00042.glb");
  EXPECT_EQ(frameFileName(1234567, ".ply"), "frame_1234567.ply");
}

}  // namespace
}  // namespace pelage::scene
