// Signed distance functions of the creature's body shapes (metres; negative inside).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

#include "pelage/anatomy/creature.h"

namespace pelage::skin::detail {

// Ellipsoid: the "k0 (k0 - 1) / k1" approximation (exact on the surface, close near it).
inline float ellipsoidDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  const Eigen::Vector3f q = s.rotation.conjugate() * (p - s.center);
  const float k0 = (q.array() / s.radii.array()).matrix().norm();
  const float k1 = (q.array() / (s.radii.array() * s.radii.array())).matrix().norm();
  if (k1 < 1e-20f) return -s.radii.minCoeff();
  return k0 * (k0 - 1.0f) / k1;
}

// Round cone: spheres of radius rFrom at `from` and rTo at `to`, joined by their tangent cone.
inline float capsuleDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  const Eigen::Vector3d a = s.from.cast<double>(), b = s.to.cast<double>(), x = p.cast<double>();
  const double r1 = static_cast<double>(s.rFrom), r2 = static_cast<double>(s.rTo);
  const Eigen::Vector3d ba = b - a;
  const double l2 = ba.squaredNorm();
  if (l2 < 1e-18) return static_cast<float>((x - a).norm() - std::max(r1, r2));
  const double rr = r1 - r2;
  const double a2 = l2 - rr * rr;
  if (a2 <= 0.0) {  // one sphere contains the other
    return static_cast<float>(std::min((x - a).norm() - r1, (x - b).norm() - r2));
  }
  const double il2 = 1.0 / l2;
  const Eigen::Vector3d pa = x - a;
  const double y = pa.dot(ba);
  const double z = y - l2;
  const double x2 = (pa * l2 - ba * y).squaredNorm();
  const double y2 = y * y * l2;
  const double z2 = z * z * l2;
  const double k = (rr > 0 ? 1.0 : (rr < 0 ? -1.0 : 0.0)) * rr * rr * x2;
  const double sz = z > 0 ? 1.0 : (z < 0 ? -1.0 : 0.0);
  const double sy = y > 0 ? 1.0 : (y < 0 ? -1.0 : 0.0);
  if (sz * a2 * z2 > k) return static_cast<float>(std::sqrt(x2 + z2) * il2 - r2);
  if (sy * a2 * y2 < k) return static_cast<float>(std::sqrt(x2 + y2) * il2 - r1);
  return static_cast<float>((std::sqrt(x2 * a2 * il2) + y * rr) * il2 - r1);
}

inline float shapeDistance(const anatomy::Shape& s, const Eigen::Vector3f& p) {
  return s.kind == anatomy::Shape::Kind::Ellipsoid ? ellipsoidDistance(s, p)
                                                   : capsuleDistance(s, p);
}

// Polynomial smooth minimum with blend radius k (Quilez): equals min(a, b) exactly when
// |a - b| >= k, and is C1 smooth.
inline float smoothMin(float a, float b, float k) {
  if (k <= 0.0f) return std::min(a, b);
  const float h = std::max(k - std::abs(a - b), 0.0f) / k;
  return std::min(a, b) - h * h * k * 0.25f;
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
