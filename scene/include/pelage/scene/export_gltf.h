// One frame of a furred creature as a glTF 2.0 binary (.glb) that any glTF viewer loads: the posed
// skin as a triangle mesh (POSITION, NORMAL, indices) and each coat's hairs (Van Gelder & Wilhelms
// 1997, sec. 3.1) as one LINES primitive (POSITION, index pairs joining consecutive points of each
// hair: the line, polyline or tessellated curve; a tube's ring centres) with COLOR_0, each point's
// hair colour (linear RGBA8, fur/colors.h; the coat's material is white so the colours show).
// Coordinates are glTF's: +Y up, metres (pelage's +Z-up point (x, y, z) is written as (y, z, x),
// which the asset's extras state). Written atomically; the data streams from the frame's buffers.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "pelage/fur/fur_params.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::scene {

// What a .glb holds.
struct GlbCounts {
  int skinVertices = 0;
  int skinTriangles = 0;
  std::array<std::int64_t, fur::kCoatCount> hairs{0, 0};
  std::array<std::int64_t, fur::kCoatCount> hairVertices{0, 0};
  std::array<std::int64_t, fur::kCoatCount> segments{0, 0};  // line segments (index pairs)
  std::uint64_t bytes = 0;                                   // file size
};

// True when `path` is a complete glTF binary: the magic, version 2, and a total length equal to
// the file's size (what --resume keeps).
bool isCompleteGlb(const std::string& path);

// The counts writeFrameGlb would write for `state`.
GlbCounts glbCounts(const Model& model, const FrameState& state);

// Writes `state` (evaluated frame with CPU hairs of `fur`, colours filled) to `path`. InputError
// naming the file if it cannot be written (unwritable directory, disk full) or would exceed glTF
// binary's 4 GiB limit. `generator` goes into asset.generator.
GlbCounts writeFrameGlb(const std::string& path, const Model& model, const Fur& fur,
                        const FrameState& state, const std::string& generator = "pelage");

}  // namespace pelage::scene
