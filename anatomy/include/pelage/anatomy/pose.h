// Per-frame state of the body: a Pose (local transforms) and the BodyState computed from it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/transform.h"

namespace pelage::anatomy {

// Per-segment local transforms (rotation, translation, scale), one per segment of the Body. The
// root segment's translation places the whole creature in the world.
struct Pose {
  std::vector<Transform> local;
};

// The rest pose: every segment at its rest local transform.
Pose restPose(const Body& body);

// World transforms and skinning matrices of every segment for one frame.
struct BodyState {
  std::vector<Eigen::Affine3f> world;     // per segment: world-from-segment
  std::vector<Eigen::Affine3f> skinning;  // per segment: world * inverseBind (bind space -> world)
};

// Forward kinematics: world[i] = world[parent(i)] * local[i] (one loop, parents first), then
// skinning[i] = world[i] * inverseBind[i]. Resizes `state` on first use; no allocation afterwards.
void forwardKinematics(const Body& body, const Pose& pose, BodyState& state);

}  // namespace pelage::anatomy
