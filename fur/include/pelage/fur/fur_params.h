// Fur parameters (Van Gelder & Wilhelms 1997, sec. 3 and Figure 2): the two coats (sec. 3.1), the
// hair count, lengths, gravity and distance culling. Plain values, validated by validateFurParams
// (and on preset load); the per-frame code trusts them.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/fur/hair_layout.h"
#include "pelage/fur/hair_style.h"
#include "pelage/util/material.h"

namespace pelage::fur {

// Where a coat's hair colour (the diffuse of its material, per hair) comes from:
//  Material: the coat's material (the paper's: one colour per coat);
//  Creature: the creature's own colours: its fur colours (a creature file's regions), else its
//    surface (glTF base colour x texture x vertex colour), else the coat's material;
//  Texture: the surface colour (base colour x texture x vertex colour; needs a textured or coloured
//    skin); Vertex: the vertex colours (COLOR_0, or a creature file's fur colours);
//  Map: the preset's colour map at the root's texture coordinates.
enum class ColorSource { Material, Creature, Texture, Vertex, Map };
inline constexpr int kColorSourceCount = 5;
// "material", "creature", "texture", "vertex", "map".
std::string_view colorSourceName(ColorSource source);
// The accepted names, for messages: "material, creature, texture, vertex, map".
std::string colorSourceNames();
// The colour source of that name, if any.
std::optional<ColorSource> findColorSource(std::string_view name);
// Parses a colour source name; InputError naming `where` and the accepted names.
ColorSource parseColorSource(std::string_view name, const std::string& where);

// A coat's colour model (Van Gelder & Wilhelms 1997, sec. 1: fur "may vary widely in color on
// different parts of the body, or even on a single hair"): the source colour at the root, times
// the tint, varied per hair (hue and value, seeded), graded from root to tip.
struct CoatColor {
  ColorSource source = ColorSource::Material;
  Eigen::Vector3f tint{1.0f, 1.0f, 1.0f};      // multiplies the source colour, [0, 10] each
  float tipLightness = 1.0f;                   // tip = root x this, [0, 10] (without a tip colour)
  bool hasTipColor = false;                    // the tip blends to tipColor instead
  Eigen::Vector3f tipColor{1.0f, 1.0f, 1.0f};  // sRGB-encoded, as typed (util/color.h), [0, 1]
  float hueVariation = 0.0f;    // per-hair hue shift, uniform in +- this many degrees [0, 180]
  float valueVariation = 0.0f;  // per-hair brightness factor 1 + v (2u - 1), v in [0, 1]
  // True when every hair of a coat with this model on a given source colour has one colour.
  bool uniformOver(ColorSource resolved) const {
    return resolved == ColorSource::Material && tipLightness == 1.0f && !hasTipColor &&
           hueVariation == 0.0f && valueVariation == 0.0f;
  }
};

// Groom maps (images on the skin's UV layout; paths as given, relative ones resolved against the
// preset file's folder when read from a file): density scales the hairs a triangle gets, length
// multiplies each hair's length (grey 0.5: half), color is the Map colour source. "" = none.
struct GroomMapPaths {
  std::string density, length, color;
  bool any() const { return !density.empty() || !length.empty() || !color.empty(); }
};

// A hair's width (its diameter), tapering linearly from the root to the tip, in millimetres. The
// paper draws hairs as 1-pixel lines (sec. 3.3); a physical width lets the renderer draw each hair
// with its coverage of the pixel at any distance, tubes (sec. 3.8) take it as their diameter, and
// the exports write it per point.
struct StrandWidth {
  float rootMm = 0.4f;  // [0.001, 20]
  float tipMm = 0.02f;  // [0, 20]
  // The width at t in [0, 1] along the hair (0 = root), in metres.
  float metersAt(float t) const { return 1e-3f * (rootMm + (tipMm - rootMm) * t); }
};

// Frizz (beyond the paper): seeded noise added to each hair's points toward the tip, on top of the
// paper's shape (fur/hair_math.h frizzOffset). At point k of K (t = k / (K - 1)) the offset is
// amplitude t^tipWeight times a random vector in [-1, 1]^3 interpolated (smoothstep) between
// lattice points 1 / frequency of the hair apart, each drawn from the hair's own seed. The root
// stays.
struct Frizz {
  float amplitudeMm = 0.0f;  // [0, 100]: 0 = off (today's hairs exactly)
  float frequency = 4.0f;    // waves along the hair [0.1, 64]
  float tipWeight = 2.0f;    // [1, 8]: the exponent of t (higher: only the tips)
};

// Clumping (beyond the paper): the coat's roots gather into clumps, about `density` per cm^2 of
// skin, each around a centre hair chosen from the roots (roots.h CoatRoots::clumpSlot); point k
// of a hair in a clump moves toward the same point of its centre hair by s(t) = strength t^shape
// (t = k / (K - 1): the root stays, the tip moves by `strength` of the way), on top of the paper's
// shape. A root joins the nearest centre within `radius`. Density 0 or strength 0: off.
struct Clump {
  float density = 0.0f;    // clumps per cm^2 [0, 100]: 0 = off (today's hairs exactly)
  float strength = 0.5f;   // [0, 1]: the share of the way to the centre hair at the tip
  float shape = 1.0f;      // [0.1, 10]: the exponent of t (higher: only the tips gather)
  float radiusMm = 10.0f;  // [0.1, 1000]: how far from a centre its clump reaches (mm)
  bool on() const { return density > 0.0f && strength > 0.0f; }
};

// The helix's ranges (CoatParams::curlRadius, curlTurns; regions and groom files too).
inline constexpr float kMaxCurlRadius = 0.5f;
inline constexpr float kMaxCurlTurns = 20.0f;
// The most a groom or a region multiplies a coat's hair width by.
inline constexpr float kMaxWidthScale = 10.0f;

// One coat (sec. 3.1): "different material characteristics, stiffness, randomness, and hair style".
struct CoatParams {
  HairStyle style = HairStyle::Polyline;
  Material material;                    // pelage::Material (sec. 3.2)
  float stiffness = 0.2f;               // [0, 1]; floppiness f = clamp(1 - stiffness, 0.02, 1)
  float normalRandomize = 0.0f;         // [0, 1]: polyline normals twist by up to r * pi
  float hairEndRandomize = 0.0f;        // [0, 2]: weightless end moves by up to r * length
  float segmentDirectionWeight = 0.0f;  // [0, 1]: w in d = normalize((1 - w) n + w s)
  float lengthFactor = 1.0f;            // [0, 10]: overcoat 1, undercoat "relative length"
  int curvePoints = 8;                  // K, curve and tube points along the hair [2, 64]
  int tubeSides = 6;                    // M, points per tube ring [3, 32]
  StrandWidth width;                    // root and tip width (mm); a tube's diameter
  float curlRadius = 0.0f;              // helix radius as a fraction of the length [0, 0.5]
  float curlTurns = 0.0f;               // helix turns along the hair [0, 20]
  Frizz frizz;                          // noise toward the tips (off)
  Clump clump;                          // gathering into clumps (off)
  CoatColor color;                      // where each hair's colour comes from
};

// A 3D region whose hairs' lengths are scaled at run time (sec. 3.2: "scale the length of ... all
// hairs in a selected 3D region"), tested at the hair root.
struct LengthRegion {
  using Shape = RegionShape;
  Shape shape = Shape::None;
  Eigen::Vector3f center = Eigen::Vector3f::Zero();  // sphere centre (m)
  float radius = 0.0f;                               // sphere radius (m)
  Eigen::Vector3f boxMin = Eigen::Vector3f::Zero();  // box corners (m, world)
  Eigen::Vector3f boxMax = Eigen::Vector3f::Zero();
  float scale = 1.0f;  // length multiplier inside [0, 10]
};

// A region of the creature groomed apart (fur/groom.h resolves it per skin vertex): `match` is a
// glob (util/path.h: '*' wildcards, case ignored) over the skin's region names (a creature file's
// regions; a glTF creature's material names and rigid mesh node names) and the body's segment
// (joint) names. A joint region covers the skin by that joint's skin weights, so its border blends
// as the paper blends per-vertex lengths (sec. 3.2). Regions apply in list order.
struct FurRegion {
  std::string match;
  float lengthScale = 1.0f;   // multiplies the length [0, 10]
  float lengthMm = 0.0f;      // > 0: the length (mm) before lengthScale, where the skin has fur;
                              // 0 = keep the length [0, 10000]
  float densityScale = 1.0f;  // multiplies the hairs per area [0, 100]
  Eigen::Vector3f tint{1.0f, 1.0f, 1.0f};  // multiplies the hairs' colour, [0, 10] each
  // The stiffness of (overcoat, undercoat) there, [0, 1] each (the coat's floppiness, sec. 3.5,
  // per hair); unset: keep.
  std::optional<Eigen::Vector2f> stiffness = std::nullopt;
  // The segment direction weight w of (overcoat, undercoat) there, [0, 1] each (sec. 3.4:
  // d = normalize((1 - w) n + w s), per hair); unset: keep.
  std::optional<Eigen::Vector2f> segmentDirectionWeight = std::nullopt;
  // The helix (sec. 3.8's curve and tube styles) of (overcoat, undercoat) there: radius as a
  // fraction of the length [0, 0.5] and turns along the hair [0, 20] (CoatParams::curlRadius,
  // curlTurns, per hair); unset: keep.
  std::optional<Eigen::Vector2f> curlRadius = std::nullopt;
  std::optional<Eigen::Vector2f> curlTurns = std::nullopt;
  // Multiplies the hair width (StrandWidth, root and tip) of (overcoat, undercoat) there,
  // [0, kMaxWidthScale] each (per hair: strands drawn and exported that wide, tubes that thick);
  // unset: keep.
  std::optional<Eigen::Vector2f> widthScale = std::nullopt;
  // Where the hairs of (overcoat, undercoat) take their colour from there (CoatColor::source):
  // each root's colour blends the sources by their weights at the root; unset: keep.
  std::optional<std::array<ColorSource, 2>> colorSource = std::nullopt;
  bool operator==(const FurRegion&) const = default;
};
inline constexpr std::size_t kMaxFurRegions = 256;

// Culling by screen scale (sec. 3.3's zoom factor): every hair is drawn while the creature appears
// at least as large as it does from the reference camera (referenceDistance, fovYDegrees,
// referenceHeight); 1/c of them when it appears c times smaller, whatever makes it smaller
// (distance, a wider field of view or a smaller image).
struct CullingParams {
  bool enabled = true;
  // Distance (m) at which every hair is drawn; 0 = where the overcoat's root is a quarter pixel
  // wide (see defaultReferenceDistance in culling.h).
  float referenceDistance = 0.0f;
  float fovYDegrees = 45.0f;   // the reference camera's vertical field of view, (1, 179)
  int referenceHeight = 1080;  // the reference image's height in pixels [16, 16384]
};

enum Coat : int { kOvercoat = 0, kUndercoat = 1 };
inline constexpr int kCoatCount = 2;

// Everything that defines a creature's fur.
struct FurParams {
  std::string name = "default";  // preset name, for messages
  std::string file;              // the preset file it was read from ("" = built in), for messages
  // Total hairs N over the skin (both coats), or, if densityPerM2 > 0, N = density * furred area.
  double hairs = 100000.0;    // [0, kMaxHairs]
  double densityPerM2 = 0.0;  // hairs per square metre of furred skin; 0 = use `hairs`
  // Or, if > 0, N such that the coats are expected to hide this share of the skin (fur/coverage.h:
  // from the furred area, the lengths and widths), (0, kMaxCoverage]; 0 = use hairs or density.
  double coverage = 0.0;
  float undercoatShare = 0.0f;  // [0, 1]: N_under = N * share, N_over = N * (1 - share)
  std::uint64_t seed = 1;
  std::array<CoatParams, kCoatCount> coats{};
  float lengthScale = 1.0f;  // [0, 10]: all hair lengths
  LengthRegion lengthRegion;
  std::vector<FurRegion> regions;        // at most kMaxFurRegions
  Eigen::Vector3f up{0.0f, 0.0f, 1.0f};  // U = -gravity direction (unit); paper: Z up
  CullingParams culling;
  GroomMapPaths maps;
  // A groom file of per-vertex values for this creature's mesh (fur/groom.h; the preset's regions
  // apply on top of it); "" = none. Relative paths as for maps.
  std::string groom;
  // Counts the hairs by a total: `hairs` = n, no density, no coverage.
  void setHairCount(double n) {
    hairs = n;
    densityPerM2 = 0.0;
    coverage = 0.0;
  }
};

// Whether some coat of `p` clumps (Clump::on).
inline bool clumps(const FurParams& p) {
  for (const CoatParams& c : p.coats)
    if (c.clump.on()) return true;
  return false;
}

// The largest hair count accepted: 20 million (40 times the paper's 500,000).
inline constexpr double kMaxHairs = 2e7;
// The largest coverage a preset may ask for (2.8 times the optical depth of 0.9).
inline constexpr double kMaxCoverage = 0.999;
// Memory the roots and hair buffers may take: 16 GiB.
inline constexpr double kMaxFurBytes = 16.0 * 1024.0 * 1024.0 * 1024.0;

// Checks every field; throws InputError naming `source`, the field and the accepted range.
// Warns (once per call) when the stiffness had to be clamped to keep floppiness >= 0.02.
// Normalises `up`.
void validateFurParams(FurParams& params, const std::string& source);

// Floppiness f = clamp(1 - stiffness, 0.02, 1) (sec. 3.5, 3.7: "floppiness is required to be at
// least .02").
inline float floppiness(float stiffness) {
  const float f = 1.0f - stiffness;
  return f < 0.02f ? 0.02f : (f > 1.0f ? 1.0f : f);
}

}  // namespace pelage::fur
