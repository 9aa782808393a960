#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pelage/anatomy/body.h"
#include "pelage/anatomy/pose.h"

namespace pelage::anatomy {
namespace {

// A chain root -> upper -> lower, each 1 m along +X from its parent.
Body chain() {
  std::vector<SegmentSpec> s(3);
  s[0].name = "root";
  s[1].name = "upper";
  s[1].parent = "root";
  s[1].rest.translation = {1, 0, 0};
  s[2].name = "lower";
  s[2].parent = "upper";
  s[2].rest.translation = {1, 0, 0};
  return makeBody(s, "chain");
}

Eigen::Quaternionf rotZ(float deg) {
  return Eigen::Quaternionf(
      Eigen::AngleAxisf(deg * static_cast<float>(M_PI) / 180.0f, Eigen::Vector3f::UnitZ()));
}

TEST(ForwardKinematics, RestPoseGivesRestWorldAndIdentitySkinning) {
  const Body b = chain();
  BodyState st;
  forwardKinematics(b, restPose(b), st);
  EXPECT_TRUE(st.world[2].translation().isApprox(Eigen::Vector3f(2, 0, 0)));
  for (const auto& s : st.skinning) EXPECT_TRUE(s.matrix().isIdentity(1e-6f));
}

// Bending "upper" by 90 degrees about Z puts "lower" at (1, 1, 0); bending "lower" too turns its
// frame by 180 degrees in total.
TEST(ForwardKinematics, ExactAnswersOnAChain) {
  const Body b = chain();
  Pose p = restPose(b);
  p.local[1].rotation = rotZ(90);
  BodyState st;
  forwardKinematics(b, p, st);
  EXPECT_TRUE(st.world[1].translation().isApprox(Eigen::Vector3f(1, 0, 0), 1e-6f));
  EXPECT_TRUE(st.world[2].translation().isApprox(Eigen::Vector3f(1, 1, 0), 1e-6f));
  // A bind-space point at the tip of "lower" (3, 0, 0) bound to "lower" moves to (1, 2, 0).
  EXPECT_TRUE(
      (st.skinning[2] * Eigen::Vector3f(3, 0, 0)).isApprox(Eigen::Vector3f(1, 2, 0), 1e-6f));
  p.local[2].rotation = rotZ(90);
  forwardKinematics(b, p, st);
  EXPECT_TRUE(
      (st.skinning[2] * Eigen::Vector3f(3, 0, 0)).isApprox(Eigen::Vector3f(0, 1, 0), 1e-5f));
  EXPECT_TRUE(st.world[2].linear().isApprox(rotZ(180).toRotationMatrix(), 1e-6f));
  // Root translation and scale carry through the chain.
  p.local[0].translation = {0, 0, 5};
  p.local[0].scale = {2, 2, 2};
  forwardKinematics(b, p, st);
  EXPECT_TRUE(st.world[2].translation().isApprox(Eigen::Vector3f(2, 2, 5), 1e-5f));
}

// Property: world transforms compose, world[i] = world[parent] * local[i], for random poses.
TEST(ForwardKinematics, ComposesForRandomPoses) {
  const Body b = chain();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BodyState st;
  for (int trial = 0; trial < 100; ++trial) {
    Pose p = restPose(b);
    for (auto& t : p.local) {
      t.rotation = Eigen::Quaternionf(u(rng), u(rng), u(rng), u(rng)).normalized();
      t.translation = {u(rng), u(rng), u(rng)};
    }
    forwardKinematics(b, p, st);
    for (int i = 1; i < 3; ++i) {
      const Eigen::Affine3f expect =
          st.world[static_cast<std::size_t>(i - 1)] * p.local[static_cast<std::size_t>(i)].matrix();
      EXPECT_TRUE(st.world[static_cast<std::size_t>(i)].matrix().isApprox(expect.matrix(), 1e-5f));
    }
    // Rigid poses keep lengths: the distance between joints 1 and 2 stays |rest translation| = 1.
    EXPECT_NEAR((st.world[2].translation() - st.world[1].translation()).norm(),
                p.local[2].translation.norm(), 1e-5f);
  }
}

}  // namespace
}  // namespace pelage::anatomy
