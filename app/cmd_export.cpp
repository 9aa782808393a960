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

void FurSettings::add(CLI::App& cmd) {
  cmd.add_option("--fur-set", settings,
                 "Set any fur parameter by its preset-file field, FIELD=VALUE (repeatable), e.g. "
                 "overcoat.stiffness=0.6, undercoat.diffuse=[0.3,0.2,0.1], overcoat.style=curve, "
                 "overcoat.curl.turns=3, culling.enabled=false (fields: models/presets/README.md)");
}

fur::FurParams FurSettings::apply(const fur::FurParams& params) const {
  if (settings.empty()) return params;
  nlohmann::json doc = nlohmann::json::parse(fur::furPresetJson(params));
  for (const std::string& s : settings) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
      inputError("--fur-set '", s, "' is not FIELD=VALUE (e.g. overcoat.stiffness=0.6)");
    const std::string field = s.substr(0, eq), text = s.substr(eq + 1);
    nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
    if (value.is_discarded()) value = text;  // a bare word: a string (e.g. a style name)
    std::string pointer;
    std::size_t start = 0;
    for (;;) {
      const std::size_t dot = field.find('.', start);
      const std::string part =
          field.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (part.empty()) inputError("--fur-set '", s, "': empty field name in '", field, "'");
      pointer += "/" + part;
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    const nlohmann::json::json_pointer ptr(pointer);
    // The parent must be an object that the preset format has (unknown fields fail on parse).
    if (!ptr.parent_pointer().empty() &&
        (!doc.contains(ptr.parent_pointer()) || !doc[ptr.parent_pointer()].is_object()))
      inputError("--fur-set '", s, "': no field group '", field.substr(0, field.rfind('.')),
                 "' (accepted: overcoat, undercoat, culling, lengthRegion, or top-level fields)");
    // "hairs" and "density" exclude each other: setting one drops the other.
    if (pointer == "/hairs") doc.erase("density");
    if (pointer == "/density") doc.erase("hairs");
    doc[ptr] = value;
  }
  return fur::parseFurPreset(doc.dump(), "--fur-set options");
}

namespace {

struct ExportArgs {
  ModelArgs model;
  FurArgs fur;
  FurSettings furSet;
  ClipFramesArgs range;
  std::string format;
  std::string out;
  DynamicsArgs dynamics;
};

void runExport(ExportArgs& a) {
  if (a.format != "usda" && a.format != "ply" && a.format != "glb")
    inputError("--format '", a.format, "' (accepted: usda, ply, glb)");
  if (!(a.range.fps >= 1.0 && a.range.fps <= 1000.0))
    inputError("--fps ", a.range.fps, " is out of range [1, 1000]");
  const scene::FrameRange range = scene::parseFrameRange(a.range.frames);
  const int first = range.first, last = range.last;
  // Output place first: a bad path fails before the model is built.
  if (a.format == "usda") {
    if (fs::path(a.out).extension() != ".usda")
      inputError("--out ", a.out, ": a USD ASCII layer must end in .usda");
    const fs::path parent = fs::path(a.out).parent_path();
    ensureWritableDirectory(parent.empty() ? std::string(".") : parent.string());
  } else {
    ensureWritableDirectory(a.out);
  }
  fur::FurParams params = a.furSet.apply(a.fur.resolve());
  params.culling.enabled = false;  // export writes every hair in every frame
  const fur::DynamicsParams dynamics = a.dynamics.resolve();
  scene::DynamicsClock clock = a.dynamics.clock();
  clock.fps = a.range.fps;
  scene::Model model = a.model.load();
  const int clip = scene::resolveClip(model, a.range.clip);
  if (a.dynamics.enabled() && clip < 0)
    inputError("--dynamics on needs a clip (--clip): the rest pose does not move");
  const scene::Fur fur = scene::growFur(model, params, "fur '" + params.name + "'");
  std::printf(
      "export: %s (%d triangles), %s, fur %s: %lld hairs%s, frames %d..%d at %g fps -> %s\n",
      model.name.c_str(), model.skin.numTriangles(),
      clip >= 0 ? ("clip " + model.clips[static_cast<std::size_t>(clip)].name).c_str()
                : "rest pose",
      params.name.c_str(), static_cast<long long>(fur.roots.total()),
      a.dynamics.enabled() ? " (dynamic)" : "", first, last, a.range.fps, a.out.c_str());
  std::fflush(stdout);

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
  scene::PlaybackOptions po;
  po.clip = clip;
  po.framesPerSecond = a.range.fps;
  po.hairSource = scene::HairSource::Cpu;  // export writes the CPU fur model's hairs
  po.dynamics = a.dynamics.enabled();
  po.dynamicsParams = dynamics;
  po.preRollFrames = clock.preRollFrames;
  scene::Playback playback(model, fur, po);
  const scene::FrameState& state = playback.state();
  for (int f = first; f <= last; ++f) {
    playback.poseFrame(f);
    playback.evaluateFur(state.skinBounds.center());  // culling is off: every hair
    if (usd) {
      usd->addFrame(f, state);
    } else if (a.format == "ply") {
      fur::writeHairPly(
          (fs::path(a.out) / scene::frameFileName(f, ".ply")).string(), state.fur,
          str("model ", model.name, ", frame ", f, " (", static_cast<double>(f) / a.range.fps,
              " s), fur ", params.name, ", seed ", params.seed));
    } else {
      scene::writeFrameGlb((fs::path(a.out) / scene::frameFileName(f, ".glb")).string(), model,
                           fur.params, state, "pelage 0.1.0");
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("frame %d/%d (%d): %lld hairs, %.2f s\n", f - first + 1, last - first + 1, f,
                static_cast<long long>(state.fur.drawn()), s);
    std::fflush(stdout);
  }
  if (usd) {
    const scene::UsdExportCounts n = usd->finish();
    std::printf(
        "wrote %s: skin %d vertices, %d triangles; %lld overcoat and %lld undercoat curves; %d "
        "time samples\n",
        a.out.c_str(), n.skinVertices, n.skinTriangles, static_cast<long long>(n.curves[0]),
        static_cast<long long>(n.curves[1]), n.frames);
  } else {
    const std::string ext = a.format == "ply" ? ".ply" : ".glb";
    std::printf(
        "wrote %d file(s) %s\n", last - first + 1,
        (fs::path(a.out) / (scene::frameFileName(first, ext) +
                            (first == last ? "" : " .. " + scene::frameFileName(last, ext))))
            .string()
            .c_str());
  }
}

}  // namespace

void ClipFramesArgs::add(CLI::App& cmd) {
  cmd.add_option(
      "--clip", clip,
      "Clip: one of the model's (see `pelage info`; default its first) or a clip .json file");
  cmd.add_option("--frames", frames, "Frames FIRST:LAST (inclusive); frame f is clip time f / fps")
      ->capture_default_str();
  cmd.add_option("--fps", fps, "Frames per second [1, 1000]")->capture_default_str();
}

void addExportCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("export",
                                 "Write a clip's animated skin and hairs: a USD ASCII layer "
                                 "(usda), or one PLY or glTF binary (glb) "
                                 "file per frame; one frame in memory at a time");
  auto a = std::make_shared<ExportArgs>();
  a->model.add(*cmd);
  a->range.add(*cmd);
  cmd->add_option("--format", a->format,
                  "usda (one layer, time samples per frame), ply or glb (one file per frame)")
      ->required();
  cmd->add_option("--out", a->out,
                  "usda: the .usda file; ply, glb: the directory for frame_NNNNN.ply/.glb")
      ->required();
  a->fur.add(*cmd);
  a->furSet.add(*cmd);
  a->dynamics.add(*cmd, false, true);
  cmd->callback([a] { runExport(*a); });
}

}  // namespace pelage::app
