// Headless export of a clip as a frame sequence (`pelage render`): each frame is evaluated, drawn
// by the shared renderer, read back and handed to PNG encoders on worker threads, which write
// DIR/frame_NNNNN.png atomically (temporary file + rename); optionally piped in order to ffmpeg for
// an .mp4 or .gif. A frame's pixels depend only on the inputs and its frame number (its camera
// framing is computed from clip time 0 and the frame itself, never from earlier frames), so frame
// ranges rendered by separate processes equal one run byte for byte and a render farm can split a
// clip freely (docs/render-farm/).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/dynamics.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/model.h"
#include "pelage/viewer/image.h"
#include "pelage/viewer/renderer.h"

namespace pelage::viewer {

using scene::frameFileName;
using scene::FrameRange;
using scene::kMaxFrameNumber;
using scene::parseFrameRange;

// True when `path` is a complete PNG file: the signature, an IHDR chunk first and an IEND chunk at
// the very end (what a run killed mid-write cannot leave under the final name anyway).
bool isCompletePng(const std::string& path);

// A camera file (JSON): one camera, or keys along the frames, linearly interpolated and held
// beyond the first and last key:
//   {"eye": [x, y, z], "target": [x, y, z], "up": [0, 0, 1], "fovYDegrees": 35}
//   {"keys": [{"frame": 0, "eye": ..., "target": ...}, {"frame": 48, ...}], "track": true}
// Metres, world frame (Z up). "track": move with the creature (see SequenceCamera::track).
struct CameraKey {
  int frame = 0;
  Eigen::Vector3f eye{1.0f, 0.0f, 0.0f};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up = Eigen::Vector3f::UnitZ();
  float fovYDegrees = 35.0f;
};
struct CameraPath {
  std::vector<CameraKey> keys;  // frames strictly increasing
  bool track = false;
};
// Loads a camera file; InputError naming the file and field on anything malformed.
CameraPath loadCameraFile(const std::string& path);
// The path's camera at `frame` (clip planes left at their defaults).
scene::Camera cameraOnPath(const CameraPath& path, int frame, int width, int height);

// How each frame's camera is chosen.
struct SequenceCamera {
  scene::CameraPreset preset = scene::CameraPreset::ThreeQuarter;  // framed at clip time 0
  std::optional<CameraPath> path;  // a camera file instead of the preset
  // Move the camera with the creature: by the horizontal displacement of its root segment since
  // clip time 0 (always on for the follow preset).
  bool track = false;
  float fovYDegrees = 35.0f;
};

struct SequenceOptions {
  int clip = -1;  // index into model.clips; -1: the rest pose in every frame
  FrameRange frames;
  double framesPerSecond = 30.0;  // frame f shows clip time f / fps
  int width = 1280;
  int height = 720;
  int samples = -1;  // MSAA samples; -1 = 4 on a GPU, 0 on a software rasteriser
  SequenceCamera camera;
  scene::HairSource hairSource = scene::HairSource::Gpu;
  scene::HairShading shading = scene::HairShading::Paper;
  scene::HairWidth hairWidth = scene::HairWidth::Lines;
  bool shadows = false;
  // Dynamic fur (fur/dynamics.h; needs a clip): hairs from the damped ends, computed on the CPU.
  // Frame f's springs have run from frame max(0, f - preRollFrames), or from frame 0 when
  // preRollFrames is -1, so a range rendered on its own matches a whole run bit for bit.
  bool dynamics = false;
  fur::DynamicsParams dynamicsParams;
  int preRollFrames = -1;
  Eigen::Vector3f background{0.80f, 0.82f, 0.86f};
  std::string outDir;      // frames go to outDir/frame_NNNNN.png
  bool resume = false;     // skip frames whose PNG is already complete
  std::string video;       // "" or an .mp4/.gif path (ffmpeg)
  int encoderThreads = 0;  // PNG encoders; 0 = the worker thread count (util/parallel.h)
};

// Checks the options (sizes, fps, range, video extension); InputError naming the option.
void validateSequenceOptions(const SequenceOptions& options);

// Renders single frames of a sequence. Needs a current OpenGL context for its whole life.
class SequenceRenderer {
 public:
  SequenceRenderer(const scene::Model& model, const scene::Fur& fur,
                   const SequenceOptions& options);
  ~SequenceRenderer();
  SequenceRenderer(const SequenceRenderer&) = delete;
  SequenceRenderer& operator=(const SequenceRenderer&) = delete;

  // The camera of frame `frame` (evaluates the frame's pose).
  scene::Camera camera(int frame);
  // Renders frame `frame` and reads it back into `out` (RGBA8, top row first).
  RenderStats render(int frame, Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Progress after each written frame.
struct SequenceProgress {
  int done = 0;  // frames finished (written or skipped)
  int total = 0;
  int skipped = 0;  // complete frames found by --resume
  int frame = 0;    // the frame just finished
  double elapsedSeconds = 0.0;
  double framesPerSecond = 0.0;  // rendered frames per second of wall time so far
  double secondsLeft = 0.0;
};

struct SequenceReport {
  int rendered = 0;
  int skipped = 0;
  double seconds = 0.0;         // wall time, context creation excluded
  std::int64_t hairsDrawn = 0;  // in the last rendered frame
  int removedTemporaries = 0;   // stale temporary frames of killed runs removed (--resume)
};

using ProgressCallback = std::function<void(const SequenceProgress&)>;
// Writes one finished file; the default writes atomically (util/atomic_file.h). Tests inject
// failures (a full disk) here.
using FileWriter =
    std::function<void(const std::string& path, const std::vector<std::uint8_t>& bytes)>;

// Renders options.frames of `model` with `fur` (needs a current OpenGL context). Throws InputError
// for bad options, an unwritable directory, a failed write or a failed ffmpeg; frames already
// written stay complete, and no partial frame or video is left.
SequenceReport renderSequence(const scene::Model& model, const scene::Fur& fur,
                              const SequenceOptions& options, const ProgressCallback& progress = {},
                              const FileWriter& writer = {});

// The absolute path of `program` found on $PATH, or "" (used to find ffmpeg).
std::string findOnPath(const std::string& program);

// Encodes frames to an .mp4 (H.264, yuv420p) or .gif (per-frame palettes) by piping raw RGBA to
// the ffmpeg program. The output appears under its name only when ffmpeg succeeded.
class VideoEncoder {
 public:
  // InputError when ffmpeg is not on $PATH (naming the Debian package), the extension is not .mp4
  // or .gif, or ffmpeg cannot be started.
  VideoEncoder(const std::string& path, int width, int height, double framesPerSecond);
  ~VideoEncoder();  // stops ffmpeg and removes its temporary output unless finish() succeeded
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  void addFrame(const Image& image);  // in order; InputError (with ffmpeg's message) if it failed
  void finish();                      // InputError with ffmpeg's message if it failed
  int frames() const { return frames_; }

 private:
  [[noreturn]] void fail(const std::string& what);
  void stop();
  std::string path_, tempPath_, logPath_;
  int width_ = 0, height_ = 0;
  int pipe_ = -1;
  int pid_ = -1;
  int frames_ = 0;
  bool done_ = false;
};

}  // namespace pelage::viewer
