// Frame ranges and frame file names (render, export, analyze): frame f shows
// clip time f / fps, and its files are named by f alone, so ranges split across processes (a render
// farm) write the same files as one run.
#pragma once

#include <string>
#include <string_view>

namespace pelage::scene {

// An inclusive range of frame numbers.
struct FrameRange {
  int first = 0;
  int last = 0;
  int count() const { return last - first + 1; }
};
inline constexpr int kMaxFrameNumber = 9999999;

// Parses "A:B" (inclusive, 0 <= A <= B <= kMaxFrameNumber) or "A" (one frame); InputError naming
// `field` and the accepted form otherwise. The one frame-range parser.
FrameRange parseFrameRange(std::string_view text, std::string_view field = "frames");

// "frame_00042.png" for (42, ".png"): at least 5 digits.
std::string frameFileName(int frame, std::string_view extension);

// The frame a frame file name names ("frame_00042.png" with ".png": 42), or -1.
int frameOfFileName(std::string_view name, std::string_view extension);

}  // namespace pelage::scene
