// One frame of hairs as a binary little-endian PLY file, written atomically:
//   element vertex: float x, y, z, nx, ny, nz; int hair (index into the coat's roots);
//                   uchar coat (0 overcoat, 1 undercoat); float width (metres: the coat's
//                   fur::StrandWidth at the point, tapering root to tip, times the hair's own
//                   width scale (a groom's); a tube's diameter; a culled frame's strands widened
//                   by its factor c, exportedWidth); with colours,
//                   uchar red, green, blue (8-bit sRGB, graded root to tip: colors.h
//                   pointColorsSrgb8)
//   element edge:   int vertex1, vertex2 joining consecutive points of each strand hair
//                   (line, polyline, curve)
//   element face:   list uchar int vertex_indices, the triangles of each ring hair (tube)
// Which element a style uses is its layout's topology (hair_layout.h).
// Hairs keep the FurFrame order: coat 0's hairs, then coat 1's, each hair's P points in a row.
#pragma once

#include <cstdint>
#include <string>

#include "pelage/fur/colors.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/generate.h"

namespace pelage::fur {

struct HairPlyCounts {
  std::int64_t vertices = 0;
  std::int64_t edges = 0;
  std::int64_t faces = 0;
};

// True when `path` is a complete hair PLY: its header ends, and the file is exactly as long as the
// header's element counts say (what --resume keeps).
bool isCompleteHairPly(const std::string& path);

// The element counts writeHairPly writes for `frame`.
HairPlyCounts hairPlyCounts(const FurFrame& frame);

// The width the exporters (this PLY, the glb) write for point k of drawn hair `hair` of coat
// `coat`: the coat's width at the point (tubes: their diameter) times the hair's own width scale
// (HairBuffers::widthScaleOf, a groom's), strands times the frame's culling factor c when culled
// (fewer, wider strands keep the coat's coverage, as the renderer draws them).
float exportedWidth(const FurFrame& frame, const FurParams& params, int coat, std::int64_t hair,
                    int k);

// Writes `frame` (grown with `params`: the coats' widths) to `path` (via a temporary file renamed
// on success; InputError naming the file on any failure, leaving no partial file). `comment` lines
// go into the header. With `colors` (the roots' colours; frame colours filled by fillHairColors),
// every vertex carries its colour.
HairPlyCounts writeHairPly(const std::string& path, const FurFrame& frame, const FurParams& params,
                           const std::string& comment = "", const FurColors* colors = nullptr);

}  // namespace pelage::fur
