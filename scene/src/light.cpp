#include "pelage/scene/light.h"

#include <cmath>
#include <string>

#include "pelage/util/color.h"
#include "pelage/util/error.h"

namespace pelage::scene {

Eigen::Vector3f lightDirection(float azimuthDegrees, float elevationDegrees) {
  constexpr float kPi = 3.14159265358979f;
  const float az = azimuthDegrees * kPi / 180.0f, el = elevationDegrees * kPi / 180.0f;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

void validateLightAngles(float azimuthDegrees, float elevationDegrees, std::string_view field) {
  if (!(azimuthDegrees >= -360.0f && azimuthDegrees <= 360.0f))
    fieldError(std::string(field), "azimuth ", azimuthDegrees,
               " is out of range [-360, 360] (degrees about +Z from +X)");
  if (!(elevationDegrees >= -90.0f && elevationDegrees <= 90.0f))
    fieldError(std::string(field), "elevation ", elevationDegrees,
               " is out of range [-90, 90] (degrees above the ground plane)");
}

void validateColor(const Eigen::Vector3f& rgb, std::string_view field) {
  for (int c = 0; c < 3; ++c)
    if (!(rgb[c] >= 0.0f && rgb[c] <= 1.0f))
      fieldError(std::string(field), "RGB"[c], " = ", rgb[c], " is out of range [0, 1]");
}

void validateLightIntensity(const Eigen::Vector3f& rgb, std::string_view field) {
  for (int c = 0; c < 3; ++c)
    if (!(rgb[c] >= 0.0f && rgb[c] <= kMaxLightIntensity))
      fieldError(std::string(field), "RGB"[c], " = ", rgb[c], " is out of range [0, ",
                 kMaxLightIntensity, "]");
}

Material skinMaterial(const Eigen::Vector3f& color) {
  Material m;
  m.ambient = color;
  m.diffuse = color;
  m.specular = Eigen::Vector3f::Constant(0.08f);
  m.shininess = 24.0f;
  return linearMaterial(m);
}

}  // namespace pelage::scene
