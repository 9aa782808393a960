// Encoding a frame sequence to a video (`pelage render --video`): raw RGBA frames piped to the
// ffmpeg program, H.264 .mp4 or .gif (a palette per frame).
#pragma once

#include <string>

#include "pelage/render/image.h"

namespace pelage::render {

// The absolute path of `program` found on $PATH, or "" (used to find ffmpeg).
std::string findOnPath(const std::string& program);

// Encodes frames to an .mp4 (H.264, yuv420p) or .gif (per-frame palettes) by piping raw RGBA to
// the ffmpeg program. The output appears under its name only when ffmpeg succeeded.
class VideoEncoder {
 public:
  // InputError (field "video") when ffmpeg is not on $PATH (naming the Debian package), the
  // extension is not .mp4 or .gif, or ffmpeg cannot be started.
  VideoEncoder(const std::string& path, int width, int height, double framesPerSecond);
  ~VideoEncoder();  // stops ffmpeg and removes its temporary output unless finish() succeeded
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  void addFrame(const Image& image);  // in order; InputError (with ffmpeg's message) if it failed
  void finish();                      // InputError with ffmpeg's message if it failed
  int frames() const { return frames_; }
  // Leftovers of runs killed before (their temporary video of this path, ffmpeg logs) removed.
  int removedTemporaries() const { return removedTemporaries_; }

 private:
  [[noreturn]] void fail(const std::string& what);
  void stop();
  void forgetTemporaries();
  std::string path_, tempPath_, logPath_;
  int width_ = 0, height_ = 0;
  int pipe_ = -1;
  int pid_ = -1;
  int frames_ = 0;
  int removedTemporaries_ = 0;
  bool done_ = false;
};

}  // namespace pelage::render
