#include "pelage/scene/export.h"

#include <chrono>
#include <filesystem>
#include <memory>

#include "pelage/fur/hair_ply.h"
#include "pelage/scene/export_gltf.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/enum_names.h"
#include "pelage/util/error.h"

namespace pelage::scene {
namespace fs = std::filesystem;

namespace {

constexpr auto kExportFormatNames = makeEnumNames<ExportFormat>(
    {{ExportFormat::Usda, "usda"}, {ExportFormat::Ply, "ply"}, {ExportFormat::Glb, "glb"}});

}  // namespace

std::string_view exportFormatName(ExportFormat format) {
  return kExportFormatNames.name(format);
}

ExportFormat parseExportFormat(std::string_view name) {
  if (const auto f = kExportFormatNames.find(name)) return *f;
  fieldError("format", "'", excerpt(name), "' (accepted: ", kExportFormatNames.list(), ")");
}

void validateExportOutput(const ExportOptions& o) {
  if (o.resume && o.format == ExportFormat::Usda)
    fieldError("resume",
               "applies to the per-frame formats (ply, glb); a USD layer is written whole");
  if (o.format == ExportFormat::Usda) {
    if (fs::path(o.out).extension() != ".usda")
      fieldError("out", o.out, ": a USD ASCII layer must end in .usda");
    const fs::path parent = fs::path(o.out).parent_path();
    ensureWritableDirectory(parent.empty() ? std::string(".") : parent.string());
    return;
  }
  if (std::error_code ec; fs::path(o.out).has_extension() && !fs::is_directory(o.out, ec))
    fieldError("out", o.out, ": ", exportFormatName(o.format),
               " frames go into a directory (frame_NNNNN.", exportFormatName(o.format),
               "), not a file");
  ensureWritableDirectory(o.out);
}

ExportReport exportClip(const Model& model, const Fur& fur, const ExportOptions& options,
                        const std::function<void(const ExportProgress&)>& progress) {
  validateExportOutput(options);
  PlaybackOptions po = options.playback;
  po.hairSource = HairSource::Cpu;  // export writes the CPU fur model's hairs
  validateFrameRange(options.frames);
  const int first = options.frames.first, last = options.frames.last, step = options.frames.step;
  const int clip = po.clip;
  ExportReport report;
  std::unique_ptr<UsdaWriter> usd;
  if (options.format == ExportFormat::Usda) {
    UsdExportOptions uo;
    uo.framesPerSecond = po.clock.fps;
    uo.firstFrame = first;
    uo.lastFrame = last;
    uo.comment =
        str("pelage export: ", model.name, ", ",
            clip >= 0 ? model.clips[static_cast<std::size_t>(clip)].name : "rest pose", ", fur ",
            fur.params.name, " (seed ", fur.params.seed, "), ", fur.roots.total(), " hairs");
    usd = std::make_unique<UsdaWriter>(options.out, model, fur, uo);
    report.removedTemporaries = usd->removedTemporaries();
  }
  Playback playback(model, fur, po);
  const FrameState& state = playback.state();
  const std::string ext = options.format == ExportFormat::Ply ? ".ply" : ".glb";
  auto framePath = [&](int f) { return (fs::path(options.out) / frameFileName(f, ext)).string(); };
  if (!usd && options.resume)
    report.removedTemporaries = removeStaleTemporaries(options.out, [&](const std::string& name) {
      const int f = frameOfFileName(name, ext);
      return options.frames.contains(f);
    });
  const auto t0 = std::chrono::steady_clock::now();
  ExportProgress p;
  p.total = options.frames.count();
  for (int f = first; f <= last; f += step) {
    ++p.done;
    if (!usd && options.resume &&
        (options.format == ExportFormat::Ply ? fur::isCompleteHairPly(framePath(f))
                                             : isCompleteGlb(framePath(f)))) {
      ++report.kept;
      continue;
    }
    playback.poseFrame(f);
    playback.evaluateFur(fur::FurView{});  // no culling: every hair
    switch (options.format) {
      case ExportFormat::Usda:
        usd->addFrame(f, state);
        break;
      case ExportFormat::Ply:
        fur::writeHairPly(framePath(f), state.fur, fur.params,
                          str("model ", model.name, ", frame ", f, " (", po.clock.secondsAt(f),
                              " s), fur ", fur.params.name, ", seed ", fur.params.seed),
                          &fur.colors);
        report.files.push_back(framePath(f));
        break;
      case ExportFormat::Glb:
        writeFrameGlb(framePath(f), model, fur, state, options.generator);
        report.files.push_back(framePath(f));
        break;
    }
    ++report.written;
    if (progress) {
      p.frame = f;
      p.hairs = state.fur.drawn();
      p.elapsedSeconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      progress(p);
    }
  }
  if (usd) {
    report.usd = usd->finish();
    report.files.push_back(options.out);
  }
  return report;
}

}  // namespace pelage::scene
