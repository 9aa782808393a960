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
  for (const char* bad : {"", ":", "5:", ":5", "a:b", "1:2:3", "1.5:3", "-1:4", "9:3", "0:10000000",
                          " 1:2", "1:2 ", "99999999999:1"}) {
    try {
      parseFrameRange(bad, "--frames");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--frames"), std::string::npos) << e.what();
    }
  }
}

TEST(FrameRange, FileNamesHaveFiveDigitsAtLeast) {
  EXPECT_EQ(frameFileName(0, ".png"), "frame_00000.png");
  EXPECT_EQ(frameFileName(42, ".glb"), "frame_00042.glb");
  EXPECT_EQ(frameFileName(1234567, ".ply"), "frame_1234567.ply");
}

}  // namespace
}  // namespace pelage::scene
