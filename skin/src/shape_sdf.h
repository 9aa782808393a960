// Signed distance functions of the creature's body shapes (metres; negative inside).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "pelage/anatomy/creature.h"

namespace pelage::skin::detail {

// The signed distance to shape s (shape_sdf.cpp): an ellipsoid's "k0 (k0 - 1) / k1" approximation
// (exact on the surface, close near it), or a round cone's exact distance.
float shapeDistance(const anatomy::Shape& s, const Eigen::Vector3f& p);

// The blend radius of shape s in the creature's smooth union (its own, or the creature's).
inline float shapeBlend(const anatomy::Creature& c, const anatomy::Shape& s) {
  return s.blend >= 0.0f ? s.blend : c.blendRadiusMeters;
}

// Polynomial smooth minimum with blend radius k (Quilez): equals min(a, b) exactly when
// |a - b| >= k, and is C1 smooth.
inline float smoothMin(float a, float b, float k) {
  if (k <= 0.0f) return std::min(a, b);
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
}

// 3 t^2 - 2 t^3 on t clamped to [0, 1]: the blends across joints and region borders.
inline float smoothstep01(float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Axis-aligned bounds of a shape.
inline Eigen::AlignedBox3f shapeBounds(const anatomy::Shape& s) {
  Eigen::AlignedBox3f box;
  if (s.kind == anatomy::Shape::Kind::Ellipsoid) {
    const Eigen::Matrix3f R = s.rotation.toRotationMatrix();
    Eigen::Vector3f ext;
    for (int i = 0; i < 3; ++i)
      ext[i] = std::sqrt((R.row(i).transpose().array().square() * s.radii.array().square()).sum());
    box.extend(s.center - ext);
    box.extend(s.center + ext);
  } else {
    box.extend(s.from - Eigen::Vector3f::Constant(s.rFrom));
    box.extend(s.from + Eigen::Vector3f::Constant(s.rFrom));
    box.extend(s.to - Eigen::Vector3f::Constant(s.rTo));
    box.extend(s.to + Eigen::Vector3f::Constant(s.rTo));
  }
  return box;
}

}  // namespace pelage::skin::detail
