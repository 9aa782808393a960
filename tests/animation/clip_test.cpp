// Clip sampling: exact values for hand-made keys in each interpolation, the quaternion hemisphere,
// looping/clamping, root motion, blending, and invariants under random clips.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pelage/anatomy/body.h"
#include "pelage/animation/clip.h"

namespace pelage::animation {
namespace {

constexpr double kPi = 3.14159265358979323846;

anatomy::Body twoSegments() {
  anatomy::SegmentSpec a, b;
  a.name = "a";
  a.rest.translation = Eigen::Vector3f(0.0f, 0.0f, 1.0f);
  b.name = "b";
  b.parent = "a";
  b.rest.translation = Eigen::Vector3f(1.0f, 0.0f, 0.0f);
  b.rest.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitX()));
  return anatomy::makeBody({a, b}, "test body");
}

Eigen::Quaternionf aa(double deg, const Eigen::Vector3f& axis) {
  return Eigen::Quaternionf(
      Eigen::AngleAxisf(static_cast<float>(deg * kPi / 180.0), axis.normalized()));
}

void pushQuat(std::vector<float>& v, const Eigen::Quaternionf& q) {
  v.insert(v.end(), {q.x(), q.y(), q.z(), q.w()});
}

Channel translation(int seg, Interpolation interp, std::vector<float> times,
                    std::vector<float> values) {
  Channel c;
  c.segment = seg;
  c.path = ChannelPath::Translation;
  c.interpolation = interp;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

Eigen::Vector3f sample3(const Channel& c, double t) {
  float v[3];
  sampleChannel(c, t, v);
  return Eigen::Vector3f(v[0], v[1], v[2]);
}

Eigen::Quaternionf sampleQ(const Channel& c, double t) {
  float v[4];
  sampleChannel(c, t, v);
  return Eigen::Quaternionf(v[3], v[0], v[1], v[2]);
}

TEST(Clip, StepHoldsEachKeyUntilTheNext) {
  const Channel c = translation(0, Interpolation::Step, {0, 1, 2}, {0, 0, 0, 1, 2, 3, 5, 5, 5});
  EXPECT_EQ(sample3(c, -1.0), Eigen::Vector3f(0, 0, 0));
  EXPECT_EQ(sample3(c, 0.99), Eigen::Vector3f(0, 0, 0));
  EXPECT_EQ(sample3(c, 1.0), Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(sample3(c, 1.7), Eigen::Vector3f(1, 2, 3));
  EXPECT_EQ(sample3(c, 2.0), Eigen::Vector3f(5, 5, 5));
  EXPECT_EQ(sample3(c, 9.0), Eigen::Vector3f(5, 5, 5));
}

TEST(Clip, LinearInterpolatesTranslationExactly) {
  const Channel c = translation(0, Interpolation::Linear, {0, 1, 3}, {0, 0, 0, 1, 2, 3, 5, 2, -1});
  EXPECT_TRUE(sample3(c, 0.25).isApprox(Eigen::Vector3f(0.25f, 0.5f, 0.75f), 1e-6f));
  EXPECT_TRUE(sample3(c, 2.0).isApprox(Eigen::Vector3f(3.0f, 2.0f, 1.0f), 1e-6f));
  EXPECT_EQ(sample3(c, 1.0), Eigen::Vector3f(1, 2, 3));
}

TEST(Clip, LinearRotationIsSlerp) {
  Channel c;
  c.path = ChannelPath::Rotation;
  c.times = {0, 1};
  pushQuat(c.values, Eigen::Quaternionf::Identity());
  pushQuat(c.values, aa(90, Eigen::Vector3f::UnitZ()));
  for (double t : {0.25, 0.5, 0.8}) {
    const Eigen::Quaternionf q = sampleQ(c, t);
    EXPECT_NEAR(q.norm(), 1.0, 1e-6);
    EXPECT_NEAR(q.angularDistance(aa(90 * t, Eigen::Vector3f::UnitZ())), 0.0, 1e-5) << "t = " << t;
  }
}

// q and -q are the same rotation: interpolating from R(10 deg) to -R(30 deg) must pass through
// R(20 deg), not swing the long way round through R(-160 deg).
TEST(Clip, RotationTakesTheShortArcAcrossHemispheres) {
  const Eigen::Vector3f x = Eigen::Vector3f::UnitX();
  Channel c;
  c.path = ChannelPath::Rotation;
  c.times = {0, 1};
  pushQuat(c.values, aa(10, x));
  const Eigen::Quaternionf far = aa(30, x);
  pushQuat(c.values, Eigen::Quaternionf(-far.w(), -far.x(), -far.y(), -far.z()));
  EXPECT_NEAR(sampleQ(c, 0.5).angularDistance(aa(20, x)), 0.0, 1e-5);
  EXPECT_NEAR(sampleQ(c, 0.25).angularDistance(aa(15, x)), 0.0, 1e-5);
  // Blending poses does the same.
  anatomy::Pose a, b, out;
  a.local.resize(1);
  b.local.resize(1);
  a.local[0].rotation = aa(10, x);
  b.local[0].rotation = Eigen::Quaternionf(-far.w(), -far.x(), -far.y(), -far.z());
  blendPoses(a, b, 0.5f, out);
  EXPECT_NEAR(out.local[0].rotation.angularDistance(aa(20, x)), 0.0, 1e-5);
}

// glTF 2.0 App. C with td = 2, v0 = 0, v1 = 1, out-tangent b0 = 3, in-tangent a1 = -1 (per second):
// p(s) = h00 v0 + td h10 b0 + h01 v1 + td h11 a1; s = 0.5 -> 1.5, s = 0.25 -> 1.09375.
TEST(Clip, CubicSplineMatchesTheHermiteFormula) {
  // Per key: in-tangent, value, out-tangent (x only varies).
  const Channel c =
      translation(0, Interpolation::CubicSpline, {0, 2},
                  {9, 9, 9, 0, 0, 0, 3, 0, 0, /* key 1 */ -1, 0, 0, 1, 0, 0, 7, 7, 7});
  EXPECT_NEAR(sample3(c, 1.0).x(), 1.5, 1e-6);
  EXPECT_NEAR(sample3(c, 0.5).x(), 1.09375, 1e-6);
  EXPECT_EQ(sample3(c, 0.0), Eigen::Vector3f(0, 0, 0));  // a key's value, not its tangents
  EXPECT_EQ(sample3(c, 2.0), Eigen::Vector3f(1, 0, 0));
  // Slope at the start equals the out-tangent: (p(h) - p(0)) / h -> 3.
  const double h = 1e-3;
  EXPECT_NEAR((sample3(c, h).x() - 0.0) / h, 3.0, 1e-2);
}

TEST(Clip, CubicSplineRotationsAreUnitQuaternions) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Channel c;
  c.path = ChannelPath::Rotation;
  c.interpolation = Interpolation::CubicSpline;
  c.times = {0, 0.5, 1.5};
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 4; ++i) c.values.push_back(u(rng));  // in-tangent
    pushQuat(c.values, Eigen::Quaternionf(u(rng), u(rng), u(rng), u(rng)).normalized());
    for (int i = 0; i < 4; ++i) c.values.push_back(u(rng));  // out-tangent
  }
  for (int i = 0; i <= 100; ++i) EXPECT_NEAR(sampleQ(c, 1.5 * i / 100.0).norm(), 1.0, 1e-5);
}

TEST(Clip, LoopingWrapsAndClampedHolds) {
  const anatomy::Body body = twoSegments();
  Clip clip;
  clip.duration = 2.0f;
  clip.channels.push_back(translation(1, Interpolation::Linear, {0, 2}, {0, 0, 0, 2, 0, 0}));
  checkClip(clip, body);
  anatomy::Pose p, q;
  sampleClip(clip, body, 2.5, p);
  sampleClip(clip, body, 0.5, q);
  EXPECT_TRUE(p.local[1].translation.isApprox(q.local[1].translation));
  sampleClip(clip, body, -0.5, p);
  EXPECT_NEAR(p.local[1].translation.x(), 1.5, 1e-6);
  EXPECT_EQ(clipTime(clip, 4.5).cycles, 2);
  clip.loop = false;
  sampleClip(clip, body, 2.5, p);
  EXPECT_NEAR(p.local[1].translation.x(), 2.0, 1e-6);
  sampleClip(clip, body, -3.0, p);
  EXPECT_NEAR(p.local[1].translation.x(), 0.0, 1e-6);
}

TEST(Clip, UnanimatedSegmentsKeepTheirRestTransform) {
  const anatomy::Body body = twoSegments();
  Clip clip;
  clip.duration = 1.0f;
  clip.channels.push_back(translation(1, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 1, 1}));
  anatomy::Pose p;
  sampleClip(clip, body, 0.5, p);
  ASSERT_EQ(p.local.size(), 2u);
  EXPECT_EQ(p.local[0].translation, body.segments[0].rest.translation);
  EXPECT_TRUE(p.local[0].rotation.isApprox(body.segments[0].rest.rotation));
  // Segment 1's rotation and scale are not animated either.
  EXPECT_TRUE(p.local[1].rotation.isApprox(body.segments[1].rest.rotation));
  EXPECT_EQ(p.local[1].scale, body.segments[1].rest.scale);
}

// A travelling loop: position x(t) = t over [0, 1] with 1 m of root motion per cycle plays on
// seamlessly, x(t) = t for every t, in value and in velocity.
TEST(Clip, RootMotionMakesTravellingLoopsSeamless) {
  const anatomy::Body body = twoSegments();
  Clip clip;
  clip.duration = 1.0f;
  clip.channels.push_back(translation(0, Interpolation::Linear, {0, 1}, {0, 0, 1, 1, 0, 1}));
  clip.rootMotionSegment = 0;
  clip.rootMotion = Eigen::Vector3f(1, 0, 0);
  checkClip(clip, body);
  anatomy::Pose p;
  for (double t : {0.25, 0.999, 1.0, 1.001, 2.25, 7.5}) {
    sampleClip(clip, body, t, p);
    EXPECT_NEAR(p.local[0].translation.x(), t, 1e-5) << "t = " << t;
    EXPECT_NEAR(p.local[0].translation.z(), 1.0, 1e-6);
  }
}

TEST(Clip, SamplingReusesThePoseStorage) {
  const anatomy::Body body = twoSegments();
  Clip clip;
  clip.duration = 1.0f;
  anatomy::Pose p;
  sampleClip(clip, body, 0.1, p);
  const anatomy::Transform* data = p.local.data();
  sampleClip(clip, body, 0.7, p);
  EXPECT_EQ(p.local.data(), data);
}

TEST(Clip, BlendEndpointsAndMidpoint) {
  anatomy::Pose a, b, out;
  a.local.resize(1);
  b.local.resize(1);
  a.local[0].translation = Eigen::Vector3f(0, 0, 0);
  b.local[0].translation = Eigen::Vector3f(2, 4, 6);
  b.local[0].scale = Eigen::Vector3f(3, 3, 3);
  b.local[0].rotation = aa(60, Eigen::Vector3f::UnitY());
  blendPoses(a, b, 0.0f, out);
  EXPECT_EQ(out.local[0].translation, a.local[0].translation);
  blendPoses(a, b, 1.0f, out);
  EXPECT_TRUE(out.local[0].rotation.isApprox(b.local[0].rotation, 1e-6f));
  blendPoses(a, b, 0.5f, out);
  EXPECT_TRUE(out.local[0].translation.isApprox(Eigen::Vector3f(1, 2, 3)));
  EXPECT_TRUE(out.local[0].scale.isApprox(Eigen::Vector3f(2, 2, 2)));
  EXPECT_NEAR(out.local[0].rotation.angularDistance(aa(30, Eigen::Vector3f::UnitY())), 0.0, 1e-5);
}

TEST(Clip, SampleBlendMixesTwoClips) {
  const anatomy::Body body = twoSegments();
  Clip a, b;
  a.duration = b.duration = 1.0f;
  a.channels.push_back(translation(1, Interpolation::Linear, {0, 1}, {0, 0, 0, 1, 0, 0}));
  b.channels.push_back(translation(1, Interpolation::Linear, {0, 1}, {0, 2, 0, 0, 2, 0}));
  anatomy::Pose scratch, out;
  sampleBlend(a, 0.5, b, 0.5, 0.25f, body, scratch, out);
  EXPECT_TRUE(out.local[1].translation.isApprox(Eigen::Vector3f(0.375f, 0.5f, 0.0f), 1e-6f));
}

TEST(Clip, CrossFadeAndPhaseSync) {
  EXPECT_EQ(crossFadeWeight(0.0, 0.5), 0.0f);
  EXPECT_EQ(crossFadeWeight(0.5, 0.5), 1.0f);
  EXPECT_EQ(crossFadeWeight(0.25, 0.5), 0.5f);
  EXPECT_EQ(crossFadeWeight(0.1, 0.0), 1.0f);
  float last = 0.0f;
  for (int i = 0; i <= 50; ++i) {
    const float w = crossFadeWeight(i / 100.0, 0.5);
    EXPECT_GE(w, last);
    last = w;
  }
  Clip walk, run;
  walk.duration = 1.0f;
  run.duration = 0.5f;
  EXPECT_NEAR(syncedTime(walk, 0.25, run), 0.125, 1e-9);
  EXPECT_NEAR(syncedTime(walk, 2.5, run), 1.25, 1e-9);
}

// Random LINEAR/STEP translation channels stay inside the keys' bounding box; random rotation
// channels of every interpolation give unit quaternions.
TEST(Clip, RandomClipsKeepInvariants) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int trial = 0; trial < 50; ++trial) {
    const int nK = 1 + trial % 7;
    Channel t, r;
    t.path = ChannelPath::Translation;
    t.interpolation = trial % 2 ? Interpolation::Linear : Interpolation::Step;
    r.path = ChannelPath::Rotation;
    r.interpolation = static_cast<Interpolation>(trial % 3);
    float time = 0.0f;
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
    for (int k = 0; k < nK; ++k) {
      time += 0.1f + 0.5f * (u(rng) + 1.0f);
      t.times.push_back(time);
      r.times.push_back(time);
      const Eigen::Vector3f v(u(rng), u(rng), u(rng));
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
      t.values.insert(t.values.end(), {v.x(), v.y(), v.z()});
      const int copies = r.interpolation == Interpolation::CubicSpline ? 3 : 1;
      for (int c = 0; c < copies; ++c)
        pushQuat(r.values, Eigen::Quaternionf(u(rng), u(rng), u(rng), u(rng)).normalized());
    }
    for (int i = 0; i <= 40; ++i) {
      const double s = -0.5 + (time + 1.0) * i / 40.0;
      const Eigen::Vector3f v = sample3(t, s);
      EXPECT_TRUE((v.array() >= lo.array() - 1e-6f).all() &&
                  (v.array() <= hi.array() + 1e-6f).all());
      EXPECT_NEAR(sampleQ(r, s).norm(), 1.0, 1e-5);
    }
  }
}

TEST(Clip, CubicChannelAlignsQuaternionSigns) {
  const Eigen::Vector3f z = Eigen::Vector3f::UnitZ();
  std::vector<float> q, dq(12, 0.0f);
  pushQuat(q, aa(0, z));
  const Eigen::Quaternionf b = aa(40, z);
  pushQuat(q, Eigen::Quaternionf(-b.w(), -b.x(), -b.y(), -b.z()));
  pushQuat(q, aa(80, z));
  const Channel c = cubicChannel(0, ChannelPath::Rotation, {0, 1, 2}, q, dq);
  // Stored values (the middle of each key's in/value/out triple) agree in sign with their
  // neighbour.
  for (int k = 1; k < 3; ++k) {
    float dot = 0.0f;
    for (int i = 0; i < 4; ++i)
      dot += c.values[static_cast<std::size_t>(k * 12 + 4 + i)] *
             c.values[static_cast<std::size_t>((k - 1) * 12 + 4 + i)];
    EXPECT_GT(dot, 0.0f);
  }
  EXPECT_NEAR(sampleQ(c, 0.5).angularDistance(aa(20, z)), 0.0, 1e-5);
}

TEST(Clip, FindClipByName) {
  std::vector<Clip> clips(2);
  clips[0].name = "walk";
  clips[1].name = "run";
  EXPECT_EQ(findClip(clips, "run"), 1);
  EXPECT_EQ(findClip(clips, "fly"), -1);
}

}  // namespace
}  // namespace pelage::animation
