// Colour encodings. pelage lights and blends in linear RGB; frames, 8-bit exports and the colours
// users type (presets, creature files, colour pickers) are sRGB-encoded (IEC 61966-2-1). glTF's
// colour factors and vertex colours are linear, as the glTF specification says.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "pelage/util/material.h"

namespace pelage {

// sRGB transfer functions: encoded [0, 1] -> linear [0, 1] and back (clamped to [0, 1]).
float srgbToLinear(float encoded);
float linearToSrgb(float linear);
// Linear [0, 1] -> the nearest 8-bit sRGB code (what a PLY colour or an 8-bit image stores).
std::uint8_t linearToSrgb8(float linear);
// The decoded value of each 8-bit sRGB code (a 256-entry table).
const float* srgb8ToLinearTable();

// Component-wise srgbToLinear.
Eigen::Vector3f srgbToLinear(const Eigen::Vector3f& encoded);

// A material as typed (sRGB-encoded ambient, diffuse and specular) in the linear values lighting
// uses; the shininess is kept.
Material linearMaterial(const Material& typed);

}  // namespace pelage
