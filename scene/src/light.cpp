#include "pelage/scene/light.h"

#include <cmath>

#include "pelage/util/color.h"

namespace pelage::scene {

Eigen::Vector3f lightDirection(float azimuthDegrees, float elevationDegrees) {
  constexpr float kPi = 3.14159265358979f;
  const float az = azimuthDegrees * kPi / 180.0f, el = elevationDegrees * kPi / 180.0f;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
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
