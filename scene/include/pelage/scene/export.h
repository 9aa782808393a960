// Exporting a clip's animated skin and hairs (`pelage export`, `pelage.export` in Python): each
// frame played by the frame owner (playback.h) with every hair (no culling), written as a USD ASCII
// layer (export_usd.h), or one PLY (fur/hair_ply.h) or glTF binary (export_gltf.h) file per frame,
// one frame in memory at a time. Per-frame formats can resume: complete frames are kept, and a
// frame after skipped ones is reached as a whole run reaches it.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/scene/export_usd.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/frame_range.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"
#include "pelage/util/version.h"

namespace pelage::scene {

enum class ExportFormat { Usda, Ply, Glb };
// "usda", "ply", "glb".
std::string_view exportFormatName(ExportFormat format);
// Parses a format name; InputError naming field "format" and the accepted names.
ExportFormat parseExportFormat(std::string_view name);

struct ExportOptions {
  PlaybackOptions playback;  // clip or still pose, fps, start time, dynamics (hairs: the CPU's)
  FrameRange frames;
  ExportFormat format = ExportFormat::Ply;
  std::string out;      // usda: the .usda file; ply, glb: the directory for frame_NNNNN.*
  bool resume = false;  // ply, glb: keep complete frames, remove killed runs' temporaries
  std::string generator = std::string("pelage ") + util::kVersion;  // glb asset generator
};

// Checks the output (extension, a directory for per-frame formats, writable) and --resume's
// format; InputError naming the field ("out", "resume").
void validateExportOutput(const ExportOptions& options);

struct ExportProgress {
  int frame = 0;            // the frame just written
  int done = 0, total = 0;  // frames finished (written or kept) of the range
  std::int64_t hairs = 0;   // in the frame just written
  double elapsedSeconds = 0.0;
};

struct ExportReport {
  std::vector<std::string> files;  // the files written (the layer, or one per frame written)
  int written = 0;                 // frames written
  int kept = 0;                    // complete frames kept (resume)
  int removedTemporaries = 0;      // files of killed runs removed
  UsdExportCounts usd;             // usda: what the layer holds
};

// Exports options.frames of `model` with `fur` (culling is off: every hair). Throws InputError for
// a bad output or a failed write (nothing partial is left).
ExportReport exportClip(const Model& model, const Fur& fur, const ExportOptions& options,
                        const std::function<void(const ExportProgress&)>& progress = {});

}  // namespace pelage::scene
