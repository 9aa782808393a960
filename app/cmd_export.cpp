// `pelage export`: a clip's animated skin and hair geometry, one frame at a time (bounded memory):
// a USD ASCII layer, or one PLY or glTF binary file per frame. Also the options shared with
// `pelage render`: --fur-set and the clip lookup.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "options.h"
#include "pelage/animation/clip_file.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/export_gltf.h"
#include "pelage/scene/export_usd.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/playback.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::app {
namespace fs = std::filesystem;

namespace {

struct ExportArgs {
  ModelOptions model;
  PoseOptions pose;
  FurOptions fur;
  DynamicsOptions dynamics;
  FrameOptions range;
  CommonOptions common;
  std::string format;
  std::string out;
  bool resume = false;
};

void runExport(ExportArgs& a) {
  if (a.format != "usda" && a.format != "ply" && a.format != "glb")
    inputError("--format '", a.format, "' (accepted: usda, ply, glb)");
  a.range.validateFps();
  if (!a.range.frames.empty()) scene::parseFrameRange(a.range.frames);
  if (a.resume && a.format == "usda")
    inputError(
        "--resume applies to the per-frame formats (ply, glb); a USD layer is written "
        "whole");
  // Output place first: a bad path fails before the model is built.
  if (a.format == "usda") {
    if (fs::path(a.out).extension() != ".usda")
      inputError("--out ", a.out, ": a USD ASCII layer must end in .usda");
    const fs::path parent = fs::path(a.out).parent_path();
    ensureWritableDirectory(parent.empty() ? std::string(".") : parent.string());
  } else {
    if (fs::path(a.out).has_extension() && !fs::is_directory(a.out))
      inputError("--out ", a.out, ": ", a.format, " frames go into a directory (frame_NNNNN.",
                 a.format, "), not a file");
    ensureWritableDirectory(a.out);
  }
  fur::FurParams params = a.fur.resolve();
  params.culling.enabled = false;  // export writes every hair in every frame
  const fur::DynamicsParams dynamics = a.dynamics.resolve();
  const bool quiet = a.common.quiet;
  scene::Model model = a.model.load(quiet);
  scene::PlaybackOptions po;
  a.pose.sequence(model, po);
  const int clip = po.clip;
  if (a.dynamics.enabled() && clip < 0)
    inputError("--dynamics on needs a clip (--clip): the rest pose does not move");
  const scene::FrameRange range = a.range.range(model, clip);
  const int first = range.first, last = range.last;
  const scene::Fur fur = scene::growFur(model, params, "fur '" + params.name + "'");
  if (!quiet) {
    std::printf(
        "export: %s (%d triangles), %s, fur %s: %lld hairs%s, frames %d..%d at %g fps -> %s\n",
        model.name.c_str(), model.skin.numTriangles(),
        clip >= 0 ? ("clip " + model.clips[static_cast<std::size_t>(clip)].name).c_str()
                  : "rest pose",
        params.name.c_str(), static_cast<long long>(fur.roots.total()),
        a.dynamics.enabled() ? " (dynamic)" : "", first, last, a.range.fps, a.out.c_str());
    std::fflush(stdout);
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<scene::UsdaWriter> usd;
  if (a.format == "usda") {
    scene::UsdExportOptions uo;
    uo.framesPerSecond = a.range.fps;
    uo.firstFrame = first;
    uo.lastFrame = last;
    uo.comment =
        str("pelage export: ", model.name, ", ",
            clip >= 0 ? model.clips[static_cast<std::size_t>(clip)].name : "rest pose", ", fur ",
            params.name, " (seed ", params.seed, "), ", fur.roots.total(), " hairs");
    usd = std::make_unique<scene::UsdaWriter>(a.out, model, fur.params, uo);
  }
  po.framesPerSecond = a.range.fps;
  po.hairSource = scene::HairSource::Cpu;  // export writes the CPU fur model's hairs
  po.dynamics = a.dynamics.enabled();
  po.dynamicsParams = dynamics;
  po.preRollFrames = a.dynamics.preRoll;
  scene::Playback playback(model, fur, po);
  const scene::FrameState& state = playback.state();
  const std::string ext = a.format == "ply" ? ".ply" : ".glb";
  auto framePath = [&](int f) { return (fs::path(a.out) / scene::frameFileName(f, ext)).string(); };
  // Per-frame formats: --resume keeps the complete frames (a frame after skipped ones is reached as
  // a whole run reaches it) and removes the temporaries killed runs left for this range.
  int skipped = 0, removed = 0;
  if (!usd && a.resume)
    removed = removeStaleTemporaries(a.out, [&](const std::string& name) {
      const int f = scene::frameOfFileName(name, ext);
      return f >= first && f <= last;
    });
  for (int f = first; f <= last; ++f) {
    if (!usd && a.resume &&
        (a.format == "ply" ? fur::isCompleteHairPly(framePath(f))
                           : scene::isCompleteGlb(framePath(f)))) {
      ++skipped;
      continue;
    }
    playback.poseFrame(f);
    playback.evaluateFur(state.skinBounds.center());  // culling is off: every hair
    if (usd) {
      usd->addFrame(f, state);
    } else if (a.format == "ply") {
      fur::writeHairPly(framePath(f), state.fur,
                        str("model ", model.name, ", frame ", f, " (",
                            po.startSeconds + static_cast<double>(f) / a.range.fps, " s), fur ",
                            params.name, ", seed ", params.seed));
    } else {
      scene::writeFrameGlb(framePath(f), model, fur.params, state, "pelage 0.1.0");
    }
    if (!quiet) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("frame %d/%d (%d): %lld hairs, %.2f s\n", f - first + 1, last - first + 1, f,
                  static_cast<long long>(state.fur.drawn()), s);
      std::fflush(stdout);
    }
  }
  if (usd) {
    const scene::UsdExportCounts n = usd->finish();
    if (!quiet)
      std::printf(
          "wrote %s: skin %d vertices, %d triangles; %lld overcoat and %lld undercoat curves; %d "
          "time samples%s\n",
          a.out.c_str(), n.skinVertices, n.skinTriangles, static_cast<long long>(n.curves[0]),
          static_cast<long long>(n.curves[1]), n.frames,
          usd->removedTemporaries() > 0
              ? str("; removed ", usd->removedTemporaries(), " spool file(s) of a killed run")
                    .c_str()
              : "");
  } else if (!quiet) {
    std::printf(
        "wrote %d file(s) %s%s%s\n", last - first + 1 - skipped,
        (fs::path(a.out) / (scene::frameFileName(first, ext) +
                            (first == last ? "" : " .. " + scene::frameFileName(last, ext))))
            .string()
            .c_str(),
        skipped > 0 ? str(" (", skipped, " complete frame(s) kept by --resume)").c_str() : "",
        removed > 0 ? str("; removed ", removed, " temporary file(s) of a killed run").c_str()
                    : "");
  }
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("export",
                         "Write a clip's animated skin and hairs: a USD ASCII layer "
                         "(usda), or one PLY or glTF binary (glb) file per frame; one frame "
                         "in memory at a time");
  auto a = std::make_shared<ExportArgs>();
  a->model.add(*cmd);
  a->pose.add(*cmd);
  a->range.add(*cmd);
  cmd->add_option("--format", a->format,
                  "usda (one layer, time samples per frame), ply or glb (one file per frame)")
      ->required();
  cmd->add_option("--out", a->out,
                  "usda: the .usda file; ply, glb: the directory for frame_NNNNN.ply/.glb")
      ->required();
  cmd->add_flag("--resume", a->resume,
                "ply, glb: keep the frames already complete (a killed or retried run)");
  a->fur.add(*cmd);
  a->dynamics.add(*cmd, true);
  a->common.add(*cmd, true);
  cmd->callback([a] { runExport(*a); });
}

}  // namespace pelage::app
