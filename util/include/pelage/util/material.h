// A Phong material as typed (sRGB-encoded colours, util/color.h: linearMaterial gives the linear
// values lighting uses; a draw list's materials are linear): Van Gelder & Wilhelms 1997, sec. 3.2:
// each coat has "ambient, diffuse, and specular reflectivity" (and a shininess, Figure 2). The one
// material type: each fur coat has one (fur::CoatParams), and the skin is drawn with one
// (scene::skinMaterial).
#pragma once

#include <Eigen/Core>

namespace pelage {

struct Material {
  Eigen::Vector3f ambient{0.3f, 0.14f, 0.0f};  // [0, 1] each
  Eigen::Vector3f diffuse{0.3f, 0.14f, 0.0f};  // [0, 1] each
  Eigen::Vector3f specular{0.6f, 0.6f, 0.6f};  // [0, 1] each
  float shininess = 16.0f;                     // Phong exponent [1, 1000]
};

}  // namespace pelage
