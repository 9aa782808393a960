#include <cstddef>

#include "pelage/anatomy/pose.h"
#include "pelage/util/error.h"

namespace pelage::anatomy {

Pose restPose(const Body& body) {
  Pose p;
  p.local.reserve(body.segments.size());
  for (const Segment& s : body.segments) p.local.push_back(s.rest);
  return p;
}

void forwardKinematics(const Body& body, const Pose& pose, BodyState& state) {
  const std::size_t n = body.segments.size();
  PELAGE_CHECK(pose.local.size() == n, "pose has ", pose.local.size(), " segments, body ", n);
  if (state.world.size() != n) state.world.resize(n);
  if (state.skinning.size() != n) state.skinning.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int parent = body.segments[i].parent;
    const Eigen::Affine3f local = pose.local[i].matrix();
    state.world[i] = parent < 0 ? local : state.world[static_cast<std::size_t>(parent)] * local;
    state.skinning[i] = state.world[i] * body.inverseBind[i];
  }
}

}  // namespace pelage::anatomy
