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
#include "pelage/scene/export.h"
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
  scene::ExportOptions eo;
  eo.format = scene::parseExportFormat(a.format);
  a.range.validateFps();
  if (!a.range.frames.empty()) eo.frames = scene::parseFrameRange(a.range.frames);
  eo.out = a.out;
  eo.resume = a.resume;
  // Output place first: a bad path fails before the model is built (and a bad model removes the
  // folders made for it).
  const NewFolders folders(eo.format == scene::ExportFormat::Usda
                               ? std::filesystem::path(eo.out).parent_path().string()
                               : eo.out);
  scene::validateExportOutput(eo);
  const fur::FurParams params = a.fur.resolve();
  const fur::DynamicsParams dynamics = a.dynamics.resolve();
  const bool quiet = a.common.quiet;
  scene::Model model = a.model.load();
  scene::PlaybackOptions& po = eo.playback;
  a.pose.sequence(model, po);
  po.clock.fps = a.range.fps;
  po.dynamics = a.dynamics.enabled();
  po.dynamicsParams = dynamics;
  po.clock.preRollFrames = a.dynamics.preRoll;
  const int clip = po.clip;
  if (po.dynamics && clip < 0)
    inputError("--dynamics on needs a clip (--clip): the rest pose does not move");
  eo.frames = a.range.range(model, clip, po.clock.startSeconds, quiet);
  const int first = eo.frames.first, last = eo.frames.last;
  const scene::Fur fur = scene::growFur(model, params, "fur '" + params.name + "'");
  if (!quiet) {
    std::printf(
        "export: %s (%d triangles), %s, fur %s: %lld hairs%s, frames %d..%d at %g fps -> %s\n",
        model.name.c_str(), model.skin.numTriangles(),
        clip >= 0 ? ("clip " + model.clips[static_cast<std::size_t>(clip)].name).c_str()
                  : "rest pose",
        params.name.c_str(), static_cast<long long>(fur.roots.total()),
        po.dynamics ? " (dynamic)" : "", first, last, a.range.fps, a.out.c_str());
    std::fflush(stdout);
  }
  const scene::ExportReport r =
      scene::exportClip(model, fur, eo, [&](const scene::ExportProgress& p) {
        if (quiet) return;
        std::printf("frame %d/%d (%d): %lld hairs, %.2f s\n", p.done, p.total, p.frame,
                    static_cast<long long>(p.hairs), p.elapsedSeconds);
        std::fflush(stdout);
      });
  if (quiet) return;
  if (eo.format == scene::ExportFormat::Usda) {
    const scene::UsdExportCounts& n = r.usd;
    std::printf(
        "wrote %s: skin %d vertices, %d triangles; %lld overcoat and %lld undercoat curves; %d "
        "time samples%s\n",
        a.out.c_str(), n.skinVertices, n.skinTriangles, static_cast<long long>(n.curves[0]),
        static_cast<long long>(n.curves[1]), n.frames,
        r.removedTemporaries > 0
            ? str("; removed ", r.removedTemporaries, " spool file(s) of a killed run").c_str()
            : "");
    return;
  }
  const std::string ext = eo.format == scene::ExportFormat::Ply ? ".ply" : ".glb";
  std::printf(
      "wrote %d file(s) %s%s%s\n", r.written,
      (fs::path(a.out) / (scene::frameFileName(first, ext) +
                          (first == last ? "" : " .. " + scene::frameFileName(last, ext))))
          .string()
          .c_str(),
      r.kept > 0 ? str(" (", r.kept, " complete frame(s) kept by --resume)").c_str() : "",
      r.removedTemporaries > 0
          ? str("; removed ", r.removedTemporaries, " temporary file(s) of a killed run").c_str()
          : "");
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
