// `pelage render`: a clip as a PNG frame sequence (and optionally a video) through the headless
// renderer; frames depend only on the inputs and their frame numbers, so ranges can be split across
// processes and machines (docs/render-farm/).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "commands.h"
#include "options.h"
#include "pelage/render/gl_context.h"
#include "pelage/render/render_sequence.h"
#include "pelage/render/video_encoder.h"
#include "pelage/scene/draw_list.h"
#include "pelage/scene/frame.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"

namespace pelage::app {
namespace {

struct RenderArgs {
  ModelOptions model;
  PoseOptions pose;
  FurOptions fur;
  DynamicsOptions dynamics;
  FrameOptions range;
  ViewOptions view;
  CommonOptions common;
  std::string out;
  std::string video;
  std::string cameraFile;
  std::string pass{scene::lightPassName(scene::LightPass::All)};
  bool resume = false;
  bool sceneFiles = false;
  int encoders = 0;
};

std::string clock(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// A progress bar on a terminal (redrawn in place on stderr); plain log lines otherwise (stdout).
class Progress {
 public:
  explicit Progress(bool quiet) : quiet_(quiet), tty_(::isatty(STDERR_FILENO) == 1) {}
  void operator()(const render::SequenceProgress& p) {
    if (quiet_) return;
    const double pct = p.total > 0 ? 100.0 * p.done / p.total : 100.0;
    if (tty_) {
      constexpr int kWidth = 30;
      const int filled = static_cast<int>(kWidth * p.done / std::max(p.total, 1));
      std::string bar(static_cast<std::size_t>(filled), '#');
      bar.resize(kWidth, '.');
      std::fprintf(stderr, "\r[%s] frame %d/%d  %.2f frames/s  %s left   ", bar.c_str(), p.done,
                   p.total, p.framesPerSecond, clock(p.secondsLeft).c_str());
      if (p.done == p.total) std::fprintf(stderr, "\n");
      std::fflush(stderr);
      return;
    }
    std::printf("frame %d/%d (%.0f%%): frame_%05d.png%s, %.2f frames/s, %s left\n", p.done, p.total,
                pct, p.frame,
                p.skipped > 0 && p.done == p.skipped ? " (resumed: complete frames skipped)" : "",
                p.framesPerSecond, clock(p.secondsLeft).c_str());
    std::fflush(stdout);
  }

 private:
  bool quiet_;
  bool tty_;
};

void runRender(RenderArgs& a) {
  render::SequenceOptions o;
  a.view.validate();
  a.range.validateFps();
  if (!a.range.frames.empty()) o.frames = scene::parseFrameRange(a.range.frames);
  o.width = a.view.width();
  o.height = a.view.height();
  o.playback.clock.fps = a.range.fps;
  o.samples = a.view.samples;
  o.outDir = a.out;
  o.resume = a.resume;
  o.video = a.video;
  o.encoderThreads = a.encoders;
  o.sceneFiles = a.sceneFiles;
  o.camera.fovYDegrees = static_cast<float>(a.view.fov);
  o.camera.track = a.view.follow;
  if (!a.cameraFile.empty())
    o.camera.path = scene::loadCameraFile(a.cameraFile);
  else
    o.camera.preset = a.view.cameraPreset();
  o.playback.hairSource = a.view.source();
  o.look.hairShading = a.view.hairShading();
  o.look.lightPass = scene::parseLightPass(a.pass);
  if ((o.look.lightPass == scene::LightPass::Fibre || o.look.lightPass == scene::LightPass::Coat) &&
      o.look.hairShading != scene::HairShading::Physical)
    inputError("--pass ", a.pass,
               " is a part of the physical model's hair light: it needs "
               "--shading physical (the default), not ",
               a.view.shading);
  o.look.hairWidth = a.view.hairWidth();
  o.look.transparency = a.view.transparent();
  o.shadows = a.view.shadows;
  o.selfShadowing = a.view.selfShadowed();
  o.lightAzimuth = a.view.lightAzimuth();
  o.lightElevation = a.view.lightElevation();
  o.lightColor = a.view.keyLightColor();
  o.ambient = a.view.ambientLight();
  o.skinColor = a.view.skin();
  o.look.background = a.view.backgroundColor();
  o.transparentBackground = a.view.transparentBackground();
  const std::string ext = std::filesystem::path(o.outDir).extension().string();
  std::error_code ignored;
  if ((ext == ".png" || ext == ".jpg" || ext == ".mp4" || ext == ".gif") &&
      !std::filesystem::is_directory(o.outDir, ignored))
    inputError("--out ", o.outDir,
               " names a file; --out is the directory for frame_NNNNN.png (give the video with "
               "--video)");
  render::validateSequenceOptions(o);  // before the model is built; dynamics once the clip is known
  const fur::DynamicsParams dynamics = a.dynamics.resolve();
  const NewFolders folders(o.outDir);  // removed again if the model or a value is bad
  ensureWritableDirectory(o.outDir);
  if (!o.video.empty() && render::findOnPath("ffmpeg").empty())
    inputError("--video ", o.video,
               " needs the ffmpeg program, which is not on PATH (Debian: apt-get install ffmpeg)");
  if (!o.video.empty()) {
    // A place that cannot be written fails now, before the model is built (a temporary file
    // beside the video, removed at once).
    try {
      AtomicFileWriter probe(o.video);
    } catch (const InputError& e) {
      inputError("--video ", e.what());
    }
  }

  fur::FurParams params = a.fur.resolve();
  if (a.view.noCulling) params.culling.enabled = false;
  const bool quiet = a.common.quiet;
  scene::Model model = a.model.load();
  a.pose.sequence(model, o.playback);
  o.frames = a.range.range(model, o.playback.clip, o.playback.clock.startSeconds, quiet);
  o.playback.dynamics = a.dynamics.enabled();
  o.playback.dynamicsParams = dynamics;
  o.playback.clock.preRollFrames = a.dynamics.preRoll;
  render::validateSequenceOptions(o);
  const scene::Fur fur = scene::growFur(model, params, "fur '" + params.name + "'");
  auto context = render::createHeadlessContext();
  const render::ContextInfo& info = context->info();
  const int clip = o.playback.clip;
  if (!quiet) {
    std::printf(
        "render: %s (%d triangles), %s, fur %s: %lld hairs%s; frames %d..%d at %g fps, %dx%d -> "
        "%s/\n",
        model.name.c_str(), model.skin.numTriangles(),
        clip >= 0 ? ("clip " + model.clips[static_cast<std::size_t>(clip)].name).c_str()
                  : "rest pose",
        params.name.c_str(), static_cast<long long>(fur.roots.total()),
        o.playback.dynamics ? " (dynamic, CPU)" : "", o.frames.first, o.frames.last,
        o.playback.clock.fps, o.width, o.height, o.outDir.c_str());
    std::printf("render: %s, %s (%s); %d worker threads\n", info.renderer.c_str(),
                info.version.c_str(), info.backend.c_str(), threadCount());
    std::fflush(stdout);
  }
  Progress progress(quiet);
  const render::SequenceReport r = render::renderSequence(
      model, fur, o, [&](const render::SequenceProgress& p) { progress(p); });
  if (quiet) return;
  std::printf("rendered %d frame(s)%s in %.2f s: %.2f frames/s (%lld hairs drawn in the last)%s\n",
              r.rendered, r.skipped > 0 ? str(", skipped ", r.skipped, " complete").c_str() : "",
              r.seconds, r.seconds > 0.0 ? r.rendered / r.seconds : 0.0,
              static_cast<long long>(r.hairsDrawn),
              r.removedTemporaries > 0
                  ? str("; removed ", r.removedTemporaries, " stale temporary file(s)").c_str()
                  : "");
  if (!o.video.empty()) std::printf("wrote %s\n", o.video.c_str());
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "render",
      "Render a clip to PNG frames DIR/frame_NNNNN.png (and an .mp4/.gif) offscreen through EGL; "
      "deterministic per frame, so frame ranges can be split across processes");
  auto a = std::make_shared<RenderArgs>();
  a->model.add(*cmd);
  a->pose.add(*cmd);
  a->range.add(*cmd);
  cmd->add_option("--out", a->out, "Output directory for frame_NNNNN.png (created if missing)")
      ->required();
  cmd->add_option("--video", a->video,
                  "Also encode the frames, in order, to this .mp4 or .gif (needs ffmpeg)");
  cmd->add_flag("--resume", a->resume,
                "Skip frames whose PNG is already complete (a killed or retried run)");
  a->view.add(*cmd);
  cmd->add_option("--camera-file", a->cameraFile,
                  "Camera JSON file (one camera or keys per frame) instead of a preset");
  a->fur.add(*cmd);
  a->dynamics.add(*cmd, true);
  cmd->add_flag("--scene-files", a->sceneFiles,
                "Also write each frame as DIR/frame_NNNNN.pelscene: camera, light, skin and hairs "
                "for a path tracer (scripts/reference/; needs --hair-source cpu)");
  cmd->add_option("--pass", a->pass,
                  "Which light the frames show, as a path tracer's light passes: all (default), "
                  "hair, fibre or coat (the physical model's parts of the hairs' light), or skin; "
                  "same coverage in each, so in linear light, premultiplied by alpha, all = hair + "
                  "skin and hair = fibre + coat (give --background transparent)");
  cmd->add_option("--encoders", a->encoders, "PNG encoder threads [0, 256] (default 0: --threads)");
  a->common.add(*cmd, true);
  cmd->callback([a, cmd] {
    if (!a->cameraFile.empty() && cmd->count("--camera") > 0)
      inputError("--camera-file and --camera both set the camera: give one of them");
    runRender(*a);
  });
}

}  // namespace pelage::app
