#include "pelage/render/render_sequence.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <string_view>

#include "encoder_pool.h"
#include "pelage/render/video_encoder.h"
#include "pelage/scene/reference_scene.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"
#include "pelage/util/parallel.h"

namespace pelage::render {
namespace fs = std::filesystem;
using detail::EncoderPool;
using scene::frameFileName;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void defaultWrite(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  AtomicFileWriter w(path);
  w.write(bytes.data(), bytes.size());
  w.commit();
}

}  // namespace

void validateSequenceOptions(const SequenceOptions& o) {
  scene::validateImageSize(o.width, o.height);
  scene::validateClock(o.playback.clock);
  scene::validateFrameRange(o.frames);
  scene::validateSamples(o.samples);
  if (o.encoderThreads < 0 || o.encoderThreads > 256)
    fieldError("encoders", o.encoderThreads, " is out of range [0, 256]");
  scene::validateFov(o.camera.fovYDegrees);
  if (o.outDir.empty()) fieldError("out", ": an output directory is required");
  if (o.playback.dynamics && o.playback.clip < 0)
    fieldError("dynamics", "on needs a clip: the rest pose does not move");
  if (o.skinColor) scene::validateColor(*o.skinColor, "skin color");
  scene::validateLightAngles(o.lightAzimuth, o.lightElevation);
  scene::validateLightIntensity(o.lightColor, "light color");
  scene::validateLightIntensity(o.ambient, "ambient");
  if (o.sceneFiles && o.playback.hairSource != scene::HairSource::Cpu)
    fieldError("scene files", "needs the hairs computed on the CPU (hair source cpu)");
  if (!o.video.empty()) {
    const std::string ext = fs::path(o.video).extension().string();
    if (ext != ".mp4" && ext != ".gif")
      fieldError("video", o.video, ": the file must end in .mp4 or .gif");
  }
}

// ---- SequenceRenderer -------------------------------------------------------------------------

struct SequenceRenderer::Impl {
  SequenceOptions options;
  scene::Playback playback;
  Renderer renderer;
  const scene::DrawList* last = nullptr;  // what render() drew last

  Impl(const scene::Model& m, const scene::Fur& f, const SequenceOptions& o)
      : options(validated(o)), playback(m, f, o.playback), renderer(rendererOptions(o)) {}

  static const SequenceOptions& validated(const SequenceOptions& o) {
    validateSequenceOptions(o);
    return o;
  }
  static RendererOptions rendererOptions(const SequenceOptions& o) {
    RendererOptions ro;
    ro.samples = o.samples;
    return ro;
  }

  scene::Light light() const {
    scene::Light l;
    l.direction = scene::lightDirection(options.lightAzimuth, options.lightElevation);
    l.color = options.lightColor;
    l.ambient = options.ambient;
    l.shadows = options.shadows;
    l.selfShadowing = options.selfShadowing;
    return l;
  }
};

SequenceRenderer::SequenceRenderer(const scene::Model& model, const scene::Fur& fur,
                                   const SequenceOptions& options)
    : impl_(std::make_unique<Impl>(model, fur, options)) {}

SequenceRenderer::~SequenceRenderer() = default;

scene::Camera SequenceRenderer::camera(int frame) {
  Impl& m = *impl_;
  return m.playback.sequenceCamera(frame, m.options.camera, m.options.width, m.options.height);
}

RenderStats SequenceRenderer::render(int frame, Image& out) {
  Impl& m = *impl_;
  const std::optional<Material> skin =
      m.options.skinColor ? std::optional<Material>(scene::skinMaterial(*m.options.skinColor))
                          : std::nullopt;
  const scene::DrawList& list =
      m.playback.sequenceFrame(frame, m.options.camera, m.options.width, m.options.height,
                               m.light(), m.options.look, skin ? &*skin : nullptr);
  m.last = &list;
  const RenderStats stats = m.renderer.render(list);
  m.renderer.readPixels(
      out, m.options.transparentBackground ? FrameAlpha::Straight : FrameAlpha::Opaque);
  return stats;
}

void SequenceRenderer::writeScene(const std::string& path) const {
  const Impl& m = *impl_;
  PELAGE_CHECK(m.last, "writeScene before a frame was rendered");
  scene::writeReferenceScene(path, *m.last, m.playback.state().fur);
}

// ---- renderSequence ---------------------------------------------------------------------------

SequenceReport renderSequence(const scene::Model& model, const scene::Fur& fur,
                              const SequenceOptions& options, const ProgressCallback& progress,
                              const FileWriter& writer) {
  validateSequenceOptions(options);
  ensureWritableDirectory(options.outDir);
  SequenceReport report;
  const Clock::time_point t0 = Clock::now();
  if (options.resume)
    report.removedTemporaries =
        removeStaleTemporaries(options.outDir, [&](const std::string& name) {
          const int f = scene::frameOfFileName(name, ".png");
          return options.frames.contains(f);
        });

  // Which frames are already complete (--resume).
  const int total = options.frames.count();
  std::vector<char> done(static_cast<std::size_t>(total), 0);
  auto framePath = [&](int frame) {
    return (fs::path(options.outDir) / frameFileName(frame, ".png")).string();
  };
  if (options.resume)
    for (int i = 0; i < total; ++i)
      if (isCompletePng(framePath(options.frames.at(i)))) {
        done[static_cast<std::size_t>(i)] = 1;
        ++report.skipped;
      }

  std::unique_ptr<VideoEncoder> video;
  if (!options.video.empty())
    video = std::make_unique<VideoEncoder>(options.video, options.width, options.height,
                                           options.playback.clock.fps);
  if (video) report.removedTemporaries += video->removedTemporaries();

  SequenceRenderer sequence(model, fur, options);
  const int toRender = total - report.skipped;
  int finished = report.skipped;
  int written = 0;
  auto onWritten = [&](int frame) {
    ++written;
    ++finished;
    if (!progress) return;
    SequenceProgress p;
    p.done = finished;
    p.total = total;
    p.skipped = report.skipped;
    p.frame = frame;
    p.elapsedSeconds = secondsSince(t0);
    p.framesPerSecond = p.elapsedSeconds > 0.0 ? written / p.elapsedSeconds : 0.0;
    p.secondsLeft = p.framesPerSecond > 0.0 ? (toRender - written) / p.framesPerSecond : 0.0;
    progress(p);
  };
  if (progress && report.skipped > 0) {
    SequenceProgress p;
    p.done = finished;
    p.total = total;
    p.skipped = report.skipped;
    p.frame = options.frames.first;
    progress(p);
  }
  const int threads =
      options.encoderThreads > 0 ? options.encoderThreads : std::max(1, threadCount());
  EncoderPool pool(threads, options.width, options.height,
                   writer ? writer : FileWriter(defaultWrite), onWritten);
  for (int i = 0; i < total; ++i) {
    const int frame = options.frames.at(i);
    checkInterrupt();
    if (done[static_cast<std::size_t>(i)]) {
      if (video) {
        const Image img = readPng(framePath(frame));
        if (img.width != options.width || img.height != options.height)
          fieldError("resume", framePath(frame), ": found a ", img.width, "x", img.height,
                     " frame, not ", options.width, "x", options.height,
                     " (render into an empty directory, or without resuming)");
        video->addFrame(img);
      }
      continue;
    }
    std::unique_ptr<Image> img = pool.acquire();
    report.hairsDrawn = sequence.render(frame, *img).hairsDrawn;
    if (options.sceneFiles)
      sequence.writeScene((fs::path(options.outDir) / frameFileName(frame, ".pelscene")).string());
    if (video) video->addFrame(*img);
    pool.submit(frame, framePath(frame), std::move(img));
    ++report.rendered;
  }
  pool.drain();
  if (video) video->finish();
  report.seconds = secondsSince(t0);
  return report;
}

}  // namespace pelage::render
