#include "pelage/util/color.h"

#include <array>
#include <cmath>
#include <cstddef>

namespace pelage {

float srgbToLinear(float c) {
  if (!(c > 0.0f)) return 0.0f;
  if (c >= 1.0f) return 1.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float l) {
  if (!(l > 0.0f)) return 0.0f;
  if (l >= 1.0f) return 1.0f;
  return l <= 0.0031308f ? l * 12.92f : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t linearToSrgb8(float l) {
  return static_cast<std::uint8_t>(std::lround(linearToSrgb(l) * 255.0f));
}

const float* srgb8ToLinearTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[static_cast<std::size_t>(i)] = srgbToLinear(i / 255.0f);
    return t;
  }();
  return table.data();
}

Eigen::Vector3f srgbToLinear(const Eigen::Vector3f& e) {
  return {srgbToLinear(e.x()), srgbToLinear(e.y()), srgbToLinear(e.z())};
}

Material linearMaterial(const Material& typed) {
  Material m = typed;
  m.ambient = srgbToLinear(typed.ambient);
  m.diffuse = srgbToLinear(typed.diffuse);
  m.specular = srgbToLinear(typed.specular);
  return m;
}

}  // namespace pelage
