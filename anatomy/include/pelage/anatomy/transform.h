// A rigid-plus-scale local transform (glTF's TRS): x' = T + R (S x).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pelage::anatomy {

struct Transform {
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();
  Eigen::Vector3f translation = Eigen::Vector3f::Zero();
  Eigen::Vector3f scale = Eigen::Vector3f::Ones();

  // The 4x4 affine matrix T * R * S.
  Eigen::Affine3f matrix() const {
    Eigen::Affine3f m = Eigen::Affine3f::Identity();
    m.linear() = rotation.toRotationMatrix() * scale.asDiagonal();
    m.translation() = translation;
    return m;
  }
};

}  // namespace pelage::anatomy
