#include "pelage/scene/clock.h"

#include <algorithm>
#include <string>

#include "pelage/util/error.h"

namespace pelage::scene {

void validateFramesPerSecond(double fps, std::string_view field) {
  if (!(fps >= kMinFramesPerSecond && fps <= kMaxFramesPerSecond))
    fieldError(std::string(field), fps, " is out of range [", kMinFramesPerSecond, ", ",
               kMaxFramesPerSecond, "]");
}

void validateStartSeconds(double seconds, std::string_view field) {
  if (!(seconds >= 0.0 && seconds <= kMaxStartSeconds))
    fieldError(std::string(field), seconds, " is out of range [0, ",
               static_cast<long long>(kMaxStartSeconds), "] seconds");
}

void validatePreRoll(int frames, std::string_view field, bool allowFromStart) {
  if (frames < (allowFromStart ? -1 : 0) || frames > kMaxPreRollFrames)
    fieldError(std::string(field), frames, " is out of range [0, ", kMaxPreRollFrames, "] frames");
}

void validateClock(const Clock& clock) {
  validateFramesPerSecond(clock.fps);
  validateStartSeconds(clock.startSeconds);
  validatePreRoll(clock.preRollFrames);
}

int preRollStart(int firstFrame, const Clock& clock) {
  if (clock.preRollFrames < 0) return 0;
  return std::max(0, firstFrame - clock.preRollFrames);
}

}  // namespace pelage::scene
