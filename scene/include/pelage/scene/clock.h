// The clock of a playback: which clip time each sequence frame shows, and how far back a frame
// reached out of order starts its dynamics. One struct for every client that plays frames
// (PlaybackOptions, AnalysisOptions, the dynamics' pre-roll), with its limits and validators.
#pragma once

#include <string_view>

namespace pelage::scene {

struct Clock {
  double fps = 30.0;          // frames per second, [kMinFramesPerSecond, kMaxFramesPerSecond]
  double startSeconds = 0.0;  // the clip time of frame 0, [0, kMaxStartSeconds]
  // Frames simulated before a sequence frame reached out of order: -1, from frame 0 (exact);
  // else this many frames earlier (faster, approximately equal), [0, kMaxPreRollFrames].
  int preRollFrames = -1;

  // The clip time that sequence frame `frame` shows: startSeconds + frame / fps.
  double secondsAt(int frame) const { return startSeconds + static_cast<double>(frame) / fps; }
};

// The limits of a clock, each checked by its validator (InputError naming `field`, as every
// client reports it: the command line names the option, Python the keyword).
inline constexpr double kMinFramesPerSecond = 1.0;
inline constexpr double kMaxFramesPerSecond = 1000.0;
void validateFramesPerSecond(double fps, std::string_view field = "fps");
inline constexpr double kMaxStartSeconds = 1e6;
void validateStartSeconds(double seconds, std::string_view field = "time");
// [0, kMaxPreRollFrames], or -1 (from frame 0: the default, not a value to type) where
// `allowFromStart`.
inline constexpr int kMaxPreRollFrames = 10000000;
void validatePreRoll(int frames, std::string_view field = "preroll", bool allowFromStart = true);
// All three, with the fields "fps", "time" and "preroll".
void validateClock(const Clock& clock);

// The first frame simulated to show frames from `firstFrame` on: 0, or max(0, first - preRoll).
int preRollStart(int firstFrame, const Clock& clock);

}  // namespace pelage::scene
