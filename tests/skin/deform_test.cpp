#include "pelage/skin/deform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "pelage/util/parallel.h"
#include "support/models.h"

namespace pelage::skin {
namespace {

using test::defaultMonkey;

Eigen::Quaternionf rot(const Eigen::Vector3f& axis, float deg) {
  return Eigen::Quaternionf(
      Eigen::AngleAxisf(deg * static_cast<float>(M_PI) / 180.0f, axis.normalized()));
}

double signedVolume(const SkinMesh& s, const std::vector<Eigen::Vector3f>& p) {
  double vol = 0.0;
  for (int f = 0; f < s.numTriangles(); ++f)
    vol += static_cast<double>(p[static_cast<std::size_t>(s.triangles[3 * f])].dot(
               p[static_cast<std::size_t>(s.triangles[3 * f + 1])].cross(
                   p[static_cast<std::size_t>(s.triangles[3 * f + 2])]))) /
           6.0;
  return vol;
}

double area(const SkinMesh& s, const std::vector<Eigen::Vector3f>& p) {
  double a = 0.0;
  for (int f = 0; f < s.numTriangles(); ++f) {
    const auto& x = p[static_cast<std::size_t>(s.triangles[3 * f])];
    a += 0.5 *
         static_cast<double>((p[static_cast<std::size_t>(s.triangles[3 * f + 1])] - x)
                                 .cross(p[static_cast<std::size_t>(s.triangles[3 * f + 2])] - x)
                                 .norm());
  }
  return a;
}

TEST(Deform, RestPoseReproducesTheBindMesh) {
  const scene::Model& m = defaultMonkey();
  anatomy::BodyState st;
  anatomy::forwardKinematics(m.body, anatomy::restPose(m.body), st);
  DeformedSkin d;
  deformSkin(m.skin, st, d);
  for (int v = 0; v < m.skin.numVertices(); ++v)
    ASSERT_TRUE(d.positions[static_cast<std::size_t>(v)].isApprox(
        Eigen::Map<const Eigen::Vector3f>(m.skin.restPositions() + 3 * v), 1e-6f));
}

TEST(Deform, ARigidPoseMovesTheSkinRigidly) {
  const scene::Model& m = defaultMonkey();
  anatomy::Pose pose = anatomy::restPose(m.body);
  const Eigen::Quaternionf q = rot({1, 2, 3}, 70);
  const Eigen::Vector3f t(0.3f, -0.2f, 1.0f);
  pose.local[0].rotation = q;
  pose.local[0].translation = q * pose.local[0].translation + t;
  anatomy::BodyState st;
  anatomy::forwardKinematics(m.body, pose, st);
  DeformedSkin rest, d;
  restSkin(m.skin, rest);
  deformSkin(m.skin, st, d);
  for (std::size_t v = 0; v < d.positions.size(); ++v) {
    ASSERT_TRUE(d.positions[v].isApprox(q * rest.positions[v] + t, 1e-5f)) << v;
    ASSERT_TRUE(d.normals[v].isApprox(q * rest.normals[v], 1e-4f)) << v;
    ASSERT_TRUE(d.directions[v].isApprox(q * rest.directions[v], 1e-4f)) << v;
  }
}

Eigen::Matrix3f blendedLinear(const Binding& b, const anatomy::BodyState& st) {
  Eigen::Matrix3f R = Eigen::Matrix3f::Zero();
  for (int k = 0; k < 4; ++k)
    R += b.weight[static_cast<std::size_t>(k)] *
         st.skinning[static_cast<std::size_t>(b.segment[static_cast<std::size_t>(k)])].linear();
  return R;
}

// Faces whose normal turned against the local blended transform of their first vertex (the linear
// part of sum_i w_i S_i, applied to normals as its inverse transpose): folded-over skin.
int flippedFaces(const SkinMesh& skin, const anatomy::BodyState& st, const DeformedSkin& rest,
                 const DeformedSkin& d) {
  int flipped = 0;
  for (int f = 0; f < skin.numTriangles(); ++f) {
    const Eigen::Matrix3f R = blendedLinear(skin.bindings()[skin.triangles[3 * f]], st);
    const Eigen::Vector3f expected =
        R.inverse().transpose() * rest.faceNormals[static_cast<std::size_t>(f)];
    flipped += expected.dot(d.faceNormals[static_cast<std::size_t>(f)]) <= 0.0f;
  }
  return flipped;
}

struct Bend {
  const char* segment;
  Eigen::Vector3f axis;
  float degrees;
  int maxFlipped;  // folded faces allowed (0 except where skin folds in a crease)
};

// One joint at a time, over the ranges the monkey's clips use. Limb joints between capsules (elbow,
// knee, wrist, ankle, neck, head, tail) bend without a single folded face; where the thigh and the
// upper arm meet the torso (groin, armpit) and along the spine, linear blend skinning folds a few
// faces of the crease (< 0.03% of the skin), as real skin does.
TEST(Deform, BendingOneJointFoldsNoSkin) {
  const scene::Model& m = defaultMonkey();
  DeformedSkin rest, d;
  restSkin(m.skin, rest);
  const Bend bends[] = {{"l_forearm", {0, 1, 0}, -90, 0}, {"l_forearm", {0, 1, 0}, 90, 0},
                        {"r_shin", {0, 1, 0}, 90, 0},     {"r_shin", {0, 1, 0}, -90, 0},
                        {"l_hand", {0, 1, 0}, 60, 0},     {"l_foot", {0, 1, 0}, -50, 0},
                        {"neck", {0, 1, 0}, 30, 0},       {"neck", {0, 1, 0}, -30, 0},
                        {"head", {0, 0, 1}, 45, 0},       {"head", {0, 1, 0}, 30, 0},
                        {"tail1", {0, 1, 0}, 40, 0},      {"tail2", {0, 0, 1}, 40, 0},
                        {"tail3", {0, 1, 0}, 40, 0},      {"chest", {0, 1, 0}, -25, 0},
                        {"l_thigh", {1, 0, 0}, 30, 0},    {"l_thigh", {0, 1, 0}, 45, 10},
                        {"l_thigh", {0, 1, 0}, -45, 40},  {"l_upperarm", {1, 0, 0}, -40, 0},
                        {"l_upperarm", {0, 1, 0}, 45, 5}, {"l_upperarm", {0, 1, 0}, -45, 5},
                        {"spine", {0, 1, 0}, 20, 5},      {"spine", {1, 0, 0}, 20, 30}};
  anatomy::BodyState st;
  for (const Bend& b : bends) {
    anatomy::Pose pose = anatomy::restPose(m.body);
    const int s = m.body.find(b.segment);
    ASSERT_GE(s, 0) << b.segment;
    pose.local[static_cast<std::size_t>(s)].rotation = rot(b.axis, b.degrees);
    anatomy::forwardKinematics(m.body, pose, st);
    deformSkin(m.skin, st, d);
    const int flipped = flippedFaces(m.skin, st, rest, d);
    EXPECT_LE(flipped, b.maxFlipped) << b.segment << " by " << b.degrees << " degrees";
    std::printf("%-11s %+4.0f deg: %d folded faces\n", b.segment, static_cast<double>(b.degrees),
                flipped);
  }
}

// Several joints at once (bent elbows and knees, a turned head, a curled tail): the skin stays
// closed around nearly the same volume and area, with unit outward normals.
TEST(Deform, SamplePosesKeepAreaAndVolume) {
  const scene::Model& m = defaultMonkey();
  const anatomy::Body& b = m.body;
  auto set = [&](anatomy::Pose& p, const char* seg, const Eigen::Vector3f& axis, float deg) {
    p.local[static_cast<std::size_t>(b.find(seg))].rotation = rot(axis, deg);
  };
  std::vector<anatomy::Pose> poses(4, anatomy::restPose(b));
  set(poses[0], "l_forearm", {0, 1, 0}, -90);
  set(poses[0], "r_forearm", {0, 1, 0}, -60);
  set(poses[1], "l_shin", {0, 1, 0}, 60);
  set(poses[1], "r_shin", {0, 1, 0}, -45);
  set(poses[2], "head", {0, 0, 1}, 45);
  set(poses[2], "neck", {0, 1, 0}, 20);
  for (const char* t : {"tail2", "tail3", "tail4", "tail5"}) set(poses[3], t, {0, 1, 0}, 25);
  DeformedSkin rest, d;
  restSkin(m.skin, rest);
  const double restArea = area(m.skin, rest.positions);
  const double restVolume = signedVolume(m.skin, rest.positions);
  ASSERT_GT(restVolume, 0.0) << "faces must be oriented outward";
  anatomy::BodyState st;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    anatomy::forwardKinematics(b, poses[i], st);
    deformSkin(m.skin, st, d);
    EXPECT_EQ(flippedFaces(m.skin, st, rest, d), 0) << "pose " << i;
    for (std::size_t v = 0; v < d.normals.size(); ++v)
      ASSERT_NEAR(d.normals[v].norm(), 1.0f, 1e-5f);
    const double vol = signedVolume(m.skin, d.positions);
    EXPECT_NEAR(vol, restVolume, 0.03 * restVolume) << "pose " << i;
    const double change = area(m.skin, d.positions) / restArea - 1.0;
    EXPECT_LT(std::abs(change), 0.02) << "pose " << i;
    std::printf("pose %zu: skin area change %+.3f%%, volume change %+.3f%%\n", i, 100.0 * change,
                100.0 * (vol / restVolume - 1.0));
  }
}

TEST(Deform, IdenticalWhateverTheThreadCountAndReusesBuffers) {
  const scene::Model& m = defaultMonkey();
  anatomy::Pose pose = anatomy::restPose(m.body);
  pose.local[static_cast<std::size_t>(m.body.find("l_forearm"))].rotation = rot({0, 1, 0}, -70);
  pose.local[static_cast<std::size_t>(m.body.find("head"))].rotation = rot({0, 0, 1}, 30);
  anatomy::BodyState st;
  anatomy::forwardKinematics(m.body, pose, st);
  DeformedSkin a, b;
  setThreadCount(1);
  deformSkin(m.skin, st, a);
  const float* before = a.positions.data()->data();
  deformSkin(m.skin, st, a);
  EXPECT_EQ(before, a.positions.data()->data()) << "the second call must reuse its buffers";
  setThreadCount(2);
  deformSkin(m.skin, st, b);
  setThreadCount(0);
  const std::size_t bytes = sizeof(float) * 3 * a.positions.size();
  EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), bytes));
  EXPECT_EQ(0, std::memcmp(a.normals.data(), b.normals.data(), bytes));
  EXPECT_EQ(0, std::memcmp(a.directions.data(), b.directions.data(), bytes));
}

}  // namespace
}  // namespace pelage::skin
