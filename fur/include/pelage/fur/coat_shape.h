// What a hair style is, per coat: the constants the per-hair maths (hair_math.h) reads for one coat
// (the paper's style templates: the polyline's a(t), b(t) of sec. 3.7, the curve's Bernstein
// weights and helix of sec. 3.8, the tube's rings), built once per frame from the preset and what
// the coat's roots carry (makeCoatShape), and the layout its hairs are grown in (coatLayout).
// The struct is shared with the GPU: render/gpu_fur.cpp generates its GLSL block from the same
// member list.
#pragma once

#include <cstdint>

#include "pelage/fur/hair_style.h"

namespace pelage::fur {

struct FurParams;
struct FurRoots;
struct HairLayout;

inline constexpr int kPolylinePoints = 8;   // sec. 3.7: "eight control points"
inline constexpr int kMaxCurvePoints = 64;  // K
inline constexpr int kMaxTubeSides = 32;    // M

// Everything per-coat that the per-hair maths needs, precomputed from FurParams (makeCoatShape
// below). One description for the CPU and the GPU: the member list below declares the C++
// struct, and render/gpu_fur.cpp generates the GLSL std430 block `cs` of hair_math.glsl from the
// same list and checks every member's offset in the linked program. Members are 4-byte scalars or
// arrays of them (enums are 32-bit, flags int32 0/1), so std430 places each at its C++ offset and
// the struct is uploaded as it is.
//
// SCALAR(C++ type, GLSL type, name) and ARRAY(C++ type, GLSL type, name, size), in block order:
//  style, points: the coat's style and P (hairLayout(coat).pointsPerHair());
//  lengthMul: global length scale * coat length factor; segmentWeight w (sec. 3.4);
//  endRandomize r, floppiness f (sec. 3.5); up U, fallbackTangent (unit, perpendicular to U);
//  twist: polyline normal randomize > 0 (twist table in use);
//  comb: the coat's roots carry a groom's comb (CoatRoots::comb; combedDirection);
//  perHairFloppiness: the coat's roots carry their own floppiness (CoatRoots::floppiness, a
//    groom's stiffness; HairInput::floppiness replaces `floppiness`);
//  perHairSegmentWeight: the coat's roots carry their own segment direction weight
//    (CoatRoots::segmentWeight; HairInput::segmentWeight replaces `segmentWeight`);
//  perHairCurl: the coat's roots carry their own helix (CoatRoots::curlRadius, ::curlTurns;
//    HairInput's replace `curlRadius` and the curlCos/curlSin table: helixTurn at curlT);
//  perHairWidth: a tube coat's roots carry their own width scale (CoatRoots::widthScale;
//    HairInput::widthScale multiplies `tubeRadius`; strands take theirs when drawn and exported);
//  frizz*: the frizz (fur_params.h Frizz; addFrizz): frizz = strand points with frizz (0: off),
//    frizzRing = points per strand point (a tube's M, else 1), frizzSeed = the coat seed's 32 bits;
//    per strand point k: frizzWeight = amplitude (m) t_k^tipWeight, frizzCell = floor(t_k freq),
//    frizzBlend = smoothstep of its fraction;
//  region*: the length region (sec. 3.2), tested at the root;
//  poly*: the polyline template (sec. 3.7): P(t_i) = R + a_i (W - R) + b_i (E - R), t_i = i / 7,
//    a(t) = 2 lambda t (1 - t), b(t) = t^2, lambda = 0.5; segment i (ending at i) has direction
//    alpha_i (W - R) + beta_i (E - R), alpha_i = a_i - a_{i-1}, beta_i = b_i - b_{i-1} (point 0
//    uses segment 1), with alpha_i^2, beta_i^2 and 2 alpha_i beta_i;
//  curve*: the curve (sec. 3.8): C(t_k) = R + c1_k L n_p + c2_k L e with the Bernstein sums
//    c1 = (1-t)^2 t, c2 = 2 (1-t) t^2 + t^3; tangent weights dc1 = (1-t)(1-3t), dc2 = 4t - 3t^2;
//  curl*: the helix, radius curlRadius * L * sin(pi t_k), angle 2 pi (turns t_k + phase), curlT
//    the t_k of the angle (float);
//  tube*, ring*: M ring directions and the tube radius at each curve point.
#define PELAGE_COAT_SHAPE_MEMBERS(SCALAR, ARRAY)                        \
  SCALAR(HairStyle, int, style)                                         \
  SCALAR(std::int32_t, int, points)                                     \
  SCALAR(std::int32_t, int, curvePoints)                                \
  SCALAR(std::int32_t, int, tubeSides)                                  \
  SCALAR(std::int32_t, int, twist)                                      \
  SCALAR(std::int32_t, int, curl)                                       \
  SCALAR(std::int32_t, int, comb)                                       \
  SCALAR(std::int32_t, int, perHairFloppiness)                          \
  SCALAR(std::int32_t, int, perHairSegmentWeight)                       \
  SCALAR(std::int32_t, int, perHairCurl)                                \
  SCALAR(std::int32_t, int, perHairWidth)                               \
  SCALAR(std::int32_t, int, frizz)                                      \
  SCALAR(std::int32_t, int, frizzRing)                                  \
  SCALAR(std::int32_t, int, frizzSeed)                                  \
  SCALAR(RegionShape, int, regionShape)                                 \
  SCALAR(float, float, lengthMul)                                       \
  SCALAR(float, float, segmentWeight)                                   \
  SCALAR(float, float, endRandomize)                                    \
  SCALAR(float, float, floppiness)                                      \
  ARRAY(float, float, up, 3)                                            \
  ARRAY(float, float, fallbackTangent, 3)                               \
  ARRAY(float, float, regionCenter, 3)                                  \
  SCALAR(float, float, regionRadius2)                                   \
  ARRAY(float, float, regionMin, 3)                                     \
  ARRAY(float, float, regionMax, 3)                                     \
  SCALAR(float, float, regionScale)                                     \
  SCALAR(float, float, curlRadius)                                      \
  ARRAY(float, float, polyA, ::pelage::fur::kPolylinePoints)            \
  ARRAY(float, float, polyB, ::pelage::fur::kPolylinePoints)            \
  ARRAY(float, float, polyAlpha, ::pelage::fur::kPolylinePoints)        \
  ARRAY(float, float, polyBeta, ::pelage::fur::kPolylinePoints)         \
  ARRAY(float, float, polyAlpha2, ::pelage::fur::kPolylinePoints)       \
  ARRAY(float, float, polyBeta2, ::pelage::fur::kPolylinePoints)        \
  ARRAY(float, float, polyTwoAlphaBeta, ::pelage::fur::kPolylinePoints) \
  ARRAY(float, float, curveC1, ::pelage::fur::kMaxCurvePoints)          \
  ARRAY(float, float, curveC2, ::pelage::fur::kMaxCurvePoints)          \
  ARRAY(float, float, curveDc1, ::pelage::fur::kMaxCurvePoints)         \
  ARRAY(float, float, curveDc2, ::pelage::fur::kMaxCurvePoints)         \
  ARRAY(float, float, curlEnvelope, ::pelage::fur::kMaxCurvePoints)     \
  ARRAY(float, float, curlCos, ::pelage::fur::kMaxCurvePoints)          \
  ARRAY(float, float, curlSin, ::pelage::fur::kMaxCurvePoints)          \
  ARRAY(float, float, curlT, ::pelage::fur::kMaxCurvePoints)            \
  ARRAY(float, float, tubeRadius, ::pelage::fur::kMaxCurvePoints)       \
  ARRAY(float, float, frizzWeight, ::pelage::fur::kMaxCurvePoints)      \
  ARRAY(float, float, frizzCell, ::pelage::fur::kMaxCurvePoints)        \
  ARRAY(float, float, frizzBlend, ::pelage::fur::kMaxCurvePoints)       \
  ARRAY(float, float, ringCos, ::pelage::fur::kMaxTubeSides)            \
  ARRAY(float, float, ringSin, ::pelage::fur::kMaxTubeSides)

struct CoatShape {
#define PELAGE_SCALAR_MEMBER(cpp, glsl, name) cpp name{};
#define PELAGE_ARRAY_MEMBER(cpp, glsl, name, size) cpp name[size]{};
  PELAGE_COAT_SHAPE_MEMBERS(PELAGE_SCALAR_MEMBER, PELAGE_ARRAY_MEMBER)
#undef PELAGE_SCALAR_MEMBER
#undef PELAGE_ARRAY_MEMBER
};

// Every member is 4 bytes wide (so std430 adds no padding) and nothing sits between them.
#define PELAGE_SCALAR_SIZE(cpp, glsl, name) +sizeof(cpp)
#define PELAGE_ARRAY_SIZE(cpp, glsl, name, size) +sizeof(cpp) * (size)
static_assert(sizeof(CoatShape) ==
              0 PELAGE_COAT_SHAPE_MEMBERS(PELAGE_SCALAR_SIZE, PELAGE_ARRAY_SIZE));
#undef PELAGE_SCALAR_SIZE
#undef PELAGE_ARRAY_SIZE
#define PELAGE_SCALAR_IS_WORD(cpp, glsl, name) \
  static_assert(sizeof(cpp) == 4, #name " is not 4 bytes");
#define PELAGE_ARRAY_IS_WORD(cpp, glsl, name, size) \
  static_assert(sizeof(cpp) == 4, #name " is not 4 bytes");
PELAGE_COAT_SHAPE_MEMBERS(PELAGE_SCALAR_IS_WORD, PELAGE_ARRAY_IS_WORD)
#undef PELAGE_SCALAR_IS_WORD
#undef PELAGE_ARRAY_IS_WORD

// The per-coat constants of hair_math.h for coat `coat` of `params` (the coats' own values for
// every hair).
CoatShape makeCoatShape(const FurParams& params, int coat);
// The same, with what the coat's roots carry (a groom's comb, stiffness, segment direction weight
// and curl: CoatShape::comb, perHair*).
CoatShape makeCoatShape(const FurParams& params, const FurRoots& roots, int coat);
// The layout of a coat's hairs as grown: hairLayout(coat), curled (HairLayout::curl) where the
// roots carry a groom's curl on a curve or tube coat. What frames, exports and the GPU size by.
HairLayout coatLayout(const FurParams& params, const FurRoots& roots, int coat);

}  // namespace pelage::fur
