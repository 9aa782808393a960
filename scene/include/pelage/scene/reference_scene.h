// One frame as a path tracer needs it, to render a reference of what pelage draws (scripts/
// reference/cycles_render.py renders it in Blender Cycles): the camera, the key light and ambient,
// the background, the deformed skin with its colours, and each coat's drawn hairs as centre lines
// with their widths and colours. GL-free; written from the draw list the renderer draws.
//
// The file (little-endian): the 8 bytes "PLGSCN01", a uint64 header length H, H bytes of JSON,
// then the arrays the header names, each {"offset": bytes after the header, "count": values}:
//   {"format": "pelage reference scene", "version": 1,
//    "camera": {"eye", "target", "up": [x, y, z], "fovYDegrees", "width", "height"},
//    "light": {"direction" (towards the light, unit), "color", "ambient": linear RGB},
//    "background": linear RGB,
//    "skin": {"vertices", "triangles", "positions": float32 nV x 3, "indices": uint32 nT x 3,
//             "cornerColors": float32 nT x 3 x 3 (linear RGB at each corner)},
//    "coats": [{"coat": 0 | 1, "hairs": n, "points": K, "cullFactor": c,
//               "widths": float32 K (metres, the coat's true width at each point; the renderer
//                 widens culled strands by cullFactor),
//               "widthScales": float32 n (only where the hairs have widths of their own, a
//                 groom's: each hair's width is widths times its scale),
//               "positions": float32 n x K x 3 (each hair's centre line: its points, a tube's
//                 ring centres),
//               "colors": float32 n x 2 x 3 (linear root and tip colour; a point's is their mix
//                 by k / (K - 1), as the renderer grades it)}]}
#pragma once

#include <string>

#include "pelage/fur/generate.h"
#include "pelage/scene/draw_list.h"

namespace pelage::scene {

inline constexpr int kReferenceSceneVersion = 1;

// The file's bytes for `list` (skin and fur items with the CPU source) and the frame's hair
// buffers `hairs` (the ones the fur items point at; PELAGE_CHECK when they disagree).
std::string referenceSceneBytes(const DrawList& list, const fur::FurFrame& hairs);

// Writes them atomically (util/atomic_file.h).
void writeReferenceScene(const std::string& path, const DrawList& list, const fur::FurFrame& hairs);

}  // namespace pelage::scene
