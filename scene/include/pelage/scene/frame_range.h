// Frame ranges and frame file names (render, export, analyze): frame f shows
// clip time f / fps, and its files are named by f alone, so ranges split across processes (a render
// farm) write the same files as one run.
#pragma once

#include <string>
#include <string_view>

namespace pelage::scene {

// Frames first, first + step, ..., last (inclusive; last is first + k step).
struct FrameRange {
  int first = 0;
  int last = 0;
  int step = 1;
  int count() const { return (last - first) / step + 1; }
  int at(int i) const { return first + i * step; }  // the i-th frame, i in [0, count())
  bool contains(int frame) const {
    return frame >= first && frame <= last && (frame - first) % step == 0;
  }
};
inline constexpr int kMaxFrameNumber = 9999999;

// Checks 0 <= first <= last <= kMaxFrameNumber, step >= 1 and last on the step; InputError naming
// `field` otherwise. The one frame-range rule (every command, the Python package).
void validateFrameRange(const FrameRange& range, std::string_view field = "frames");

// Parses "A:B" (inclusive), "A:B:STEP" (every STEP-th frame from A; B is rounded down onto the
// step) or "A" (one frame), and validates it; InputError naming `field` and the accepted form
// otherwise. The one frame-range parser.
FrameRange parseFrameRange(std::string_view text, std::string_view field = "frames");

// "frame_00042.png" for (42, ".png"): at least 5 digits.
std::string frameFileName(int frame, std::string_view extension);

// The frame a frame file name names ("frame_00042.png" with ".png": 42), or -1.
int frameOfFileName(std::string_view name, std::string_view extension);

}  // namespace pelage::scene
