// Fur parameters (Van Gelder & Wilhelms 1997, sec. 3 and Figure 2): the two coats (sec. 3.1), the
// hair count, lengths, gravity and distance culling. Plain values, validated by validateFurParams
// (and on preset load); the per-frame code trusts them.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "pelage/fur/hair_layout.h"
#include "pelage/fur/hair_style.h"
#include "pelage/util/material.h"

namespace pelage::fur {

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
  float tubeRadiusMeters = 0.0002f;     // tube radius at the root [1e-6, 0.01] m
  float curlRadius = 0.0f;              // helix radius as a fraction of the length [0, 0.5]
  float curlTurns = 0.0f;               // helix turns along the hair [0, 20]
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

// Distance-based culling (sec. 3.3).
struct CullingParams {
  bool enabled = true;
  // Distance (m) at which every hair is drawn; 0 = derived from the creature's face and fovYDegrees
  // (see defaultReferenceDistance in culling.h).
  float referenceDistance = 0.0f;
  float fovYDegrees = 45.0f;  // camera vertical field of view used for the default, (1, 179)
};

enum Coat : int { kOvercoat = 0, kUndercoat = 1 };
inline constexpr int kCoatCount = 2;

// Everything that defines a creature's fur.
struct FurParams {
  std::string name = "default";  // preset name, for messages
  // Total hairs N over the skin (both coats), or, if densityPerM2 > 0, N = density * furred area.
  double hairs = 100000.0;      // [0, kMaxHairs]
  double densityPerM2 = 0.0;    // hairs per square metre of furred skin; 0 = use `hairs`
  float undercoatShare = 0.0f;  // [0, 1]: N_under = N * share, N_over = N * (1 - share)
  std::uint64_t seed = 1;
  std::array<CoatParams, kCoatCount> coats{};
  float lengthScale = 1.0f;  // [0, 10]: all hair lengths
  LengthRegion lengthRegion;
  Eigen::Vector3f up{0.0f, 0.0f, 1.0f};  // U = -gravity direction (unit); paper: Z up
  CullingParams culling;
};

// The largest hair count accepted: 20 million (40 times the paper's 500,000).
inline constexpr double kMaxHairs = 2e7;
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
