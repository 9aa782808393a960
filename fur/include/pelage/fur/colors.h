// Groom maps and hair colours. Van Gelder & Wilhelms 1997, sec. 1: fur "may vary widely in color on
// different parts of the body, or even on a single hair"; sec. 3.2: everything a hair needs is
// interpolated at its root from barycentric coordinates. Each hair's colour is computed once per
// set of roots and colour parameters (constant during playback, like the roots): its coat's
// ColorSource at the root (fur_params.h), times the tint, varied per hair in hue and value
// (seeded: the same for any thread count), and a root and a tip colour between which the hair's
// points are graded. The paper's per-coat material stays: a hair's colour is its diffuse, and its
// ambient is the colour times the coat's ambient-to-diffuse luminance ratio.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/groom.h"
#include "pelage/fur/roots.h"
#include "pelage/skin/skin_mesh.h"
#include "pelage/skin/texture.h"

namespace pelage::fur {

// The source coat colour `asked` resolves to on `skin`: Creature becomes Vertex (a creature file's
// fur colours), Texture (a surface with colours of its own) or Material; the others must be
// available: InputError naming `field` otherwise ("overcoat.color.source texture: ...").
ColorSource resolveColorSource(const skin::SkinMesh& skin, ColorSource asked, const Groom& maps,
                               const std::string& field);

// One coat's hair colours.
struct CoatColors {
  ColorSource source = ColorSource::Material;  // resolved
  bool perHair = false;  // false: every hair has `diffuse` and `ambient` (`packed` is empty)
  Eigen::Vector3f diffuse = Eigen::Vector3f::Zero();  // uniform: the coat's material, tinted
  Eigen::Vector3f ambient = Eigen::Vector3f::Zero();
  float ambientRatio = 0.0f;  // per hair: ambient = hair colour x this
  // perHair: root k's root colour at 2k and tip colour at 2k + 1, each RGBA8 with sRGB-encoded
  // R, G, B in bytes 0, 1, 2 (little-endian: R lowest); byte 3 of both is 255, or with
  // perHairWidth the hair's width scale (packHairWidth).
  std::vector<std::uint32_t> packed;
  // The roots carry a groom's width scale (CoatRoots::widthScale): each pair's alpha bytes hold
  // it, so the renderer draws every hair at its own width from the pairs it already reads (which
  // makes the coat's colours per hair even where they would all be one).
  bool perHairWidth = false;
};

struct FurColors {
  std::array<CoatColors, kCoatCount> coats;
};

// Colours every root of `roots` (grown on `skin` with `params`' count, share and seed): a groom's
// vertex tint multiplies the root colour and the tip colour (so a tinted region is darker to its
// tips).
// Deterministic and thread-count independent. InputError for an unavailable source.
FurColors colorRoots(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                     const Groom& maps);

// A hair's width scale s in [0, kMaxWidthScale] in the alpha bytes of its packed pair (root,
// tip): the 16-bit code round(s kWidthScaleCodes), low byte in the root colour's, high byte in the
// tip's; hairWidthScale decodes it (what the renderer's hair.vert does), within 1/8192 of s.
inline constexpr float kWidthScaleCodes = 4096.0f;
void packHairWidth(std::uint32_t* pair, float widthScale);
float hairWidthScale(const std::uint32_t* pair);

// Linear RGB (clamped to [0, 1]) -> packed RGBA8 sRGB, and back (the 8-bit codes decoded).
std::uint32_t packSrgb8(const Eigen::Vector3f& linear);
Eigen::Vector3f unpackSrgb8(std::uint32_t packed);

// The one root-to-tip grading of a hair's colour (the renderer's shaders do the same): the linear
// colour at parameter t along the hair (0 root, 1 tip) whose packed colours are pair[0] (root) and
// pair[1] (tip): root + t (tip - root), both decoded.
Eigen::Vector3f gradeHairColor(const std::uint32_t* pair, float t);

// Root `root`'s hair (in root order: c.packed), graded at t; the coat's diffuse when it is uniform.
Eigen::Vector3f hairColorAt(const CoatColors& c, std::int64_t root, float t);

// Drawn hair i of `hb` (in frame order: hb.colors, filled by fillHairColors), graded at t; the
// coat's diffuse when it is uniform.
Eigen::Vector3f drawnHairColorAt(const CoatColors& c, const struct HairBuffers& hb, std::int64_t i,
                                 float t);

// Copies each drawn hair's packed root and tip colour into frame.coats[c].colors (2 per drawn hair,
// through hairIds) for the coats with per-hair colours; clears the others'. After generateFur.
void fillHairColors(const FurColors& colors, struct FurFrame& frame);

// The 8-bit sRGB colour (R, G, B) of every point of `hb`'s drawn hairs, in frame order (3 bytes per
// point): the hair's colours (hb.colors, filled by fillHairColors) graded root to tip like the
// renderer grades them (HairLayout::along), or the coat's uniform colour. For exporters.
void pointColorsSrgb8(const CoatColors& colors, const struct HairBuffers& hb,
                      std::vector<std::uint8_t>& rgb);

// Hue rotation by `degrees` and the other per-hair colour steps, exposed for tests: HSV hue of a
// linear RGB colour shifted, saturation and value kept.
Eigen::Vector3f shiftHue(const Eigen::Vector3f& rgb, float degrees);

}  // namespace pelage::fur
