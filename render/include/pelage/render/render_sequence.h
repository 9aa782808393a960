// Headless export of a clip as a frame sequence (`pelage render`): each frame is played by the
// frame owner (scene/playback.h), drawn by the shared renderer, read back and handed to PNG
// encoders on worker threads, which write DIR/frame_NNNNN.png atomically (temporary file +
// rename); optionally piped in order to ffmpeg for an .mp4 or .gif (video_encoder.h). A frame's
// pixels depend only on the inputs and its frame number (its camera framing is computed from clip
// time 0 and the frame itself, never from earlier frames), so frame ranges rendered by separate
// processes equal one run byte for byte and a render farm can split a clip freely
// (docs/render-farm/).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pelage/render/image.h"
#include "pelage/render/renderer.h"
#include "pelage/scene/camera.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"

namespace pelage::render {

using scene::FrameRange;

struct SequenceOptions {
  // What is played: the clip (-1: the still pose), frames per second (frame f shows clip time
  // f / fps), the hair source and dynamic fur with its pre-roll.
  scene::PlaybackOptions playback;
  FrameRange frames;
  int width = 1280;  // image size, [16, 16384] per side
  int height = 720;
  int samples = -1;  // MSAA samples [0, 64]; -1 = 4 on a GPU, 0 on a software rasteriser
  scene::CameraRig camera;
  // The look: hair shading, lines or strands, background colour (the hair source is the
  // playback's).
  scene::DrawOptions look;
  // Frames with straight alpha, 0 where nothing is drawn (FrameAlpha::Straight); else opaque.
  bool transparentBackground = false;
  std::optional<Eigen::Vector3f> skinColor;  // the skin's diffuse colour; none: the model's
  bool shadows = false;
  bool selfShadowing = true;  // the fur's deep opacity shadow (scene::Light::selfShadowing)
  // The key light's place (scene::lightDirection), degrees.
  float lightAzimuth = scene::kKeyLightAzimuthDegrees;
  float lightElevation = scene::kKeyLightElevationDegrees;
  // The key light's colour and the ambient light (linear; scene::Light's defaults).
  Eigen::Vector3f lightColor = scene::Light{}.color;
  Eigen::Vector3f ambient = scene::Light{}.ambient;
  std::string outDir;      // frames go to outDir/frame_NNNNN.png
  bool resume = false;     // skip frames whose PNG is already complete
  std::string video;       // "" or an .mp4/.gif path (ffmpeg)
  int encoderThreads = 0;  // PNG encoders; 0 = the worker thread count (util/parallel.h)
  // Also write each rendered frame as a reference scene for a path tracer, outDir/
  // frame_NNNNN.pelscene (scene/reference_scene.h); needs the CPU hair source.
  bool sceneFiles = false;
};

// Checks the options (size, frames, fps, samples, encoders, field of view, output, video
// extension, dynamics without a clip); InputError naming the field ("size", "frames", ...).
void validateSequenceOptions(const SequenceOptions& options);

// Renders single frames of a sequence. Needs a current OpenGL context for its whole life.
class SequenceRenderer {
 public:
  SequenceRenderer(const scene::Model& model, const scene::Fur& fur,
                   const SequenceOptions& options);
  ~SequenceRenderer();
  SequenceRenderer(const SequenceRenderer&) = delete;
  SequenceRenderer& operator=(const SequenceRenderer&) = delete;

  // The camera of frame `frame` (poses the frame).
  scene::Camera camera(int frame);
  // Renders frame `frame` and reads it back into `out` (RGBA8, top row first).
  RenderStats render(int frame, Image& out);
  // Writes the frame render() drew last as a reference scene (scene/reference_scene.h; the CPU
  // hair source).
  void writeScene(const std::string& path) const;

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

}  // namespace pelage::render
