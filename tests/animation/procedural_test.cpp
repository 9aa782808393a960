// The monkey's procedural clips: seamless loops (value and velocity), the baked keyframes match the
// functions, and each clip does what it promises (tumble turns upside down and rolls forward on the
// ground, hang keeps its hand still, walk plants its feet, shake and idle stay in place).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pelage/anatomy/pose.h"
#include "pelage/animation/procedural.h"
#include "pelage/scene/model.h"
#include "pelage/skin/deform.h"
#include "pelage/util/error.h"

namespace pelage::animation {
namespace {

const anatomy::Creature& monkey() {
  static const anatomy::Creature c = scene::builtinCreature("monkey");
  return c;
}
const anatomy::Body& monkeyBody() {
  return monkey().body;
}

const std::vector<Clip>& baked() {
  static const std::vector<Clip> clips = monkeyClips(monkey());
  return clips;
}

const Clip& clipNamed(const std::string& name) {
  const int i = findClip(baked(), name);
  EXPECT_GE(i, 0) << name;
  return baked()[static_cast<std::size_t>(std::max(i, 0))];
}

// World joint positions of a pose.
std::vector<Eigen::Vector3f> joints(const anatomy::Pose& pose) {
  anatomy::BodyState st;
  anatomy::forwardKinematics(monkeyBody(), pose, st);
  std::vector<Eigen::Vector3f> out;
  for (const auto& w : st.world) out.push_back(w.translation());
  return out;
}

std::vector<Eigen::Vector3f> bakedJoints(const Clip& clip, double t) {
  anatomy::Pose p;
  sampleClip(clip, monkeyBody(), t, p);
  return joints(p);
}

std::vector<Eigen::Vector3f> exactJoints(const std::string& name, double t) {
  anatomy::Pose p;
  evaluateMonkeyClip(monkey(), name, t, p);
  return joints(p);
}

float maxDistance(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b) {
  float d = 0.0f;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, (a[i] - b[i]).norm());
  return d;
}

int seg(const char* name) {
  return monkeyBody().find(name);
}

TEST(Procedural, FiveLoopingClips) {
  const std::vector<std::string> expect = {"walk", "tumble", "hang", "shake", "idle"};
  EXPECT_EQ(monkeyClipNames(), expect);
  ASSERT_EQ(baked().size(), 5u);
  for (const Clip& c : baked()) {
    EXPECT_TRUE(c.loop) << c.name;
    EXPECT_NEAR(c.duration, monkeyClipDuration(c.name), 1e-6) << c.name;
    EXPECT_GT(c.duration, 0.5f);
    checkClip(c, monkeyBody());
  }
}

// The baked CUBICSPLINE clip reproduces the procedural function between keys (joint positions
// within 2 mm), so every consumer plays the same motion.
TEST(Procedural, BakedClipsMatchTheFunctions) {
  for (const Clip& c : baked()) {
    float worst = 0.0f;
    for (int i = 0; i < 97; ++i) {
      const double t = c.duration * (i + 0.37) / 97.0;
      worst = std::max(worst, maxDistance(bakedJoints(c, t), exactJoints(c.name, t)));
    }
    EXPECT_LT(worst, 0.002f) << c.name;
  }
}

// No jump at the loop point: joint positions just before and after it differ by no more than the
// motion over that interval, and the velocities on both sides agree.
TEST(Procedural, LoopsAreSeamlessInValueAndVelocity) {
  const double h = 1e-3;
  for (const Clip& c : baked()) {
    const double D = c.duration;
    const auto b2 = bakedJoints(c, D - 2 * h), b1 = bakedJoints(c, D - h);
    const auto a1 = bakedJoints(c, D + h), a2 = bakedJoints(c, D + 2 * h);
    float speed = 0.0f, dv = 0.0f;
    for (std::size_t j = 0; j < b1.size(); ++j) {
      const Eigen::Vector3f vb = (b1[j] - b2[j]) / static_cast<float>(h),
                            va = (a2[j] - a1[j]) / static_cast<float>(h);
      speed = std::max(speed, vb.norm());
      dv = std::max(dv, (va - vb).norm());
    }
    // Across the loop (2h) a joint moves about speed * 2h; a jump would be far larger.
    EXPECT_LT(maxDistance(b1, a1), 3.0f * speed * static_cast<float>(h) + 1e-4f) << c.name;
    EXPECT_LT(dv, 0.05f * speed + 0.02f) << c.name << " speed " << speed;
  }
}

TEST(Procedural, TumbleIsUpsideDownMidClipAndRollsForwardOnTheGround) {
  const Clip& c = clipNamed("tumble");
  const int pelvis = seg("pelvis");
  auto up = [&](double t) {
    anatomy::Pose p;
    sampleClip(c, monkeyBody(), t, p);
    return (p.local[static_cast<std::size_t>(pelvis)].rotation * Eigen::Vector3f::UnitZ()).z();
  };
  EXPECT_GT(up(0.0), 0.99f);
  EXPECT_LT(up(c.duration / 2), -0.99f);  // upside down
  // Forward roll: a quarter in, the head is below the pelvis; the body has moved forward (+X).
  const auto q = bakedJoints(c, c.duration / 4);
  EXPECT_LT(q[static_cast<std::size_t>(seg("head"))].z(), q[static_cast<std::size_t>(pelvis)].z());
  EXPECT_GT(c.rootMotion.x(), 0.3f);
  EXPECT_NEAR(c.rootMotion.y(), 0.0f, 1e-6f);
  EXPECT_NEAR(c.rootMotion.z(), 0.0f, 1e-5f);
  float lowest = 1e9f;
  for (int i = 0; i < 60; ++i)
    for (const auto& j : bakedJoints(c, c.duration * i / 60.0)) lowest = std::min(lowest, j.z());
  EXPECT_GT(lowest, 0.0f);   // it rolls on the ground, never through it
  EXPECT_LT(lowest, 0.12f);  // ...and stays close to it
}

// The root's world up vector (after forward kinematics) makes one full forward turn about the
// lateral axis per cycle: up at the start; pointing forward (+X) a quarter in, as the body pitches
// head-first; straight down mid-clip (upside down; the spine and the curled chest too); back up
// at the end. The pitch angle only ever increases: a roll, not a rocking motion.
TEST(Procedural, TumbleRootUpVectorFlipsAndTurnsOnce) {
  const Clip& c = clipNamed("tumble");
  auto upOf = [&](double t, const char* segment) {
    anatomy::Pose p;
    sampleClip(c, monkeyBody(), t, p);
    anatomy::BodyState st;
    anatomy::forwardKinematics(monkeyBody(), p, st);
    return Eigen::Vector3f(st.world[static_cast<std::size_t>(seg(segment))].linear() *
                           Eigen::Vector3f::UnitZ());
  };
  const double D = c.duration;
  EXPECT_GT(upOf(0.0, "pelvis").z(), 0.999f);
  const Eigen::Vector3f quarter = upOf(D / 4, "pelvis");
  EXPECT_NEAR(quarter.z(), 0.0f, 0.01f);
  EXPECT_GT(quarter.x(), 0.99f);  // up now points forward: the body pitched head-first
  const Eigen::Vector3f mid = upOf(D / 2, "pelvis");
  EXPECT_LT(mid.z(), -0.999f);  // upside down
  EXPECT_NEAR(mid.y(), 0.0f, 1e-3f);
  for (const char* s : {"spine", "chest"}) EXPECT_LT(upOf(D / 2, s).z(), -0.5f) << s;
  EXPECT_LT(upOf(3 * D / 4, "pelvis").x(), -0.99f);
  EXPECT_GT(upOf(D, "pelvis").z(), 0.999f);
  // The pitch angle atan2(up.x, up.z) increases monotonically through a full turn.
  double previous = 0.0, unwrapped = 0.0;
  const int n = 120;
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector3f u = upOf(D * i / n, "pelvis");
    EXPECT_NEAR(u.y(), 0.0f, 1e-3f);
    const double a = std::atan2(static_cast<double>(u.x()), static_cast<double>(u.z()));
    const double step = std::remainder(a - previous, 2.0 * M_PI);  // in [-pi, pi]
    EXPECT_GT(step, 0.5 * (2.0 * M_PI / n)) << "at t = " << D * i / n;
    EXPECT_LT(step, 1.5 * (2.0 * M_PI / n)) << "at t = " << D * i / n;
    unwrapped += step;
    previous = a;
  }
  EXPECT_NEAR(unwrapped, 2.0 * M_PI, 1e-3);
}

TEST(Procedural, HangKeepsTheGripStillAndSwings) {
  const int hand = seg("l_hand");
  auto grip = [&](const anatomy::Pose& p) {
    anatomy::BodyState st;
    anatomy::forwardKinematics(monkeyBody(), p, st);
    return Eigen::Vector3f(st.world[static_cast<std::size_t>(hand)] *
                           Eigen::Vector3f(0.012f, 0.0f, -0.03f));
  };
  const Clip& c = clipNamed("hang");
  anatomy::Pose p;
  evaluateMonkeyClip(monkey(), "hang", 0.0, p);
  const Eigen::Vector3f g0 = grip(p);
  float exact = 0.0f, bakedDrift = 0.0f, pelvisTravel = 0.0f;
  const Eigen::Vector3f pelvis0 = joints(p)[static_cast<std::size_t>(seg("pelvis"))];
  for (int i = 1; i < 50; ++i) {
    const double t = c.duration * i / 50.0;
    evaluateMonkeyClip(monkey(), "hang", t, p);
    exact = std::max(exact, (grip(p) - g0).norm());
    pelvisTravel = std::max(pelvisTravel,
                            (joints(p)[static_cast<std::size_t>(seg("pelvis"))] - pelvis0).norm());
    sampleClip(c, monkeyBody(), t, p);
    bakedDrift = std::max(bakedDrift, (grip(p) - g0).norm());
  }
  EXPECT_LT(exact, 1e-5f);
  EXPECT_LT(bakedDrift, 0.002f);
  EXPECT_GT(pelvisTravel, 0.05f);  // the body swings
  EXPECT_GT(g0.z(), 0.6f);         // the hand holds on above the monkey
  // Hanging: the head is above the pelvis, the feet below it.
  const auto j = exactJoints("hang", 0.0);
  EXPECT_GT(j[static_cast<std::size_t>(seg("head"))].z(),
            j[static_cast<std::size_t>(seg("pelvis"))].z() + 0.15f);
  EXPECT_LT(j[static_cast<std::size_t>(seg("l_foot"))].z(),
            j[static_cast<std::size_t>(seg("pelvis"))].z());
}

// A planted foot does not slide: whenever an ankle or wrist is at its lowest (on the ground), its
// horizontal speed is near zero while the body walks at 0.22 m/s.
TEST(Procedural, WalkPlantsItsFeet) {
  const Clip& c = clipNamed("walk");
  EXPECT_NEAR(c.rootMotion.x(), 0.22f * c.duration, 1e-4f);
  const int n = 200;
  const double dt = c.duration / n;
  for (const char* end : {"l_foot", "r_foot", "l_hand", "r_hand"}) {
    const int e = seg(end);
    std::vector<Eigen::Vector3f> path;
    for (int i = 0; i <= n; ++i)
      path.push_back(exactJoints("walk", i * dt)[static_cast<std::size_t>(e)]);
    float low = 1e9f;
    for (const auto& p : path) low = std::min(low, p.z());
    int planted = 0;
    for (int i = 0; i < n; ++i) {
      if (path[static_cast<std::size_t>(i)].z() > low + 1e-4f ||
          path[static_cast<std::size_t>(i) + 1].z() > low + 1e-4f)
        continue;
      ++planted;
      const float speed =
          (path[static_cast<std::size_t>(i) + 1] - path[static_cast<std::size_t>(i)])
              .head<2>()
              .norm() /
          static_cast<float>(dt);
      EXPECT_LT(speed, 0.03f) << end << " at t = " << i * dt;
    }
    EXPECT_GT(planted, n / 3) << end;  // planted for most of the cycle (duty factor 0.62)
    // ...and it does swing forward in the rest of the cycle.
    float lift = 0.0f;
    for (const auto& p : path) lift = std::max(lift, p.z() - low);
    EXPECT_GT(lift, 0.02f) << end;
  }
}

TEST(Procedural, ShakeAndIdleStayInPlace) {
  for (const char* name : {"shake", "idle", "hang"})
    EXPECT_EQ(clipNamed(name).rootMotion, Eigen::Vector3f::Zero()) << name;
  // shake starts and ends at rest.
  anatomy::Pose p;
  evaluateMonkeyClip(monkey(), "shake", 0.0, p);
  const anatomy::Pose rest = anatomy::restPose(monkeyBody());
  for (std::size_t i = 0; i < p.local.size(); ++i) {
    EXPECT_NEAR(p.local[i].rotation.angularDistance(rest.local[i].rotation), 0.0, 1e-5);
    EXPECT_TRUE(p.local[i].translation.isApprox(rest.local[i].translation, 1e-6f));
  }
  // ...and shakes hard in the middle: the head rolls by more than 10 degrees.
  evaluateMonkeyClip(monkey(), "shake", monkeyClipDuration("shake") / 2 + 0.05, p);
  EXPECT_GT(p.local[static_cast<std::size_t>(seg("head"))].rotation.angularDistance(
                Eigen::Quaternionf::Identity()),
            0.17f);
}

// The deformed skin stays finite and near the creature for every clip (bounded by the rest bounds
// grown by 0.5 m, plus the distance travelled).
TEST(Procedural, SkinStaysFiniteAndBounded) {
  scene::LoadOptions opt;
  opt.triangles = 8000;
  const scene::Model m = scene::loadModel("monkey", opt);
  ASSERT_EQ(m.clips.size(), 5u);
  skin::DeformedSkin rest, d;
  skin::restSkin(m.skin, rest);
  Eigen::AlignedBox3f restBox;
  for (const auto& p : rest.positions) restBox.extend(p);
  anatomy::Pose pose;
  anatomy::BodyState st;
  float tumbleLow = 1e9f, tumbleHigh = -1e9f;
  for (const Clip& c : m.clips)
    for (int i = 0; i <= 12; ++i) {
      const double t = 2.0 * c.duration * i / 12.0;
      sampleClip(c, m.body, t, pose);
      anatomy::forwardKinematics(m.body, pose, st);
      skin::deformSkin(m.skin, st, d);
      Eigen::AlignedBox3f box = restBox;
      box.extend(restBox.max() + 2.0f * c.rootMotion);
      box.min().array() -= 0.5f;
      box.max().array() += 0.5f;
      float low = 1e9f;
      for (const auto& p : d.positions) {
        ASSERT_TRUE(p.allFinite()) << c.name;
        ASSERT_TRUE(box.contains(p)) << c.name << " t " << t << ": " << p.transpose();
        low = std::min(low, p.z());
      }
      if (c.name == "tumble")
        tumbleLow = std::min(tumbleLow, low), tumbleHigh = std::max(tumbleHigh, low);
    }
  // The rolling ball's skin touches the ground all the way round: its lowest point stays within
  // [-1.5 cm, +2.5 cm] of z = 0 (the body shapes' smooth union bulges a little between shapes).
  EXPECT_GT(tumbleLow, -0.015f);
  EXPECT_LT(tumbleHigh, 0.025f);
}

TEST(Procedural, RejectsOtherSkeletonsAndBadRates) {
  anatomy::SegmentSpec root;
  root.name = "pelvis";
  const anatomy::Body other = anatomy::makeBody({root}, "other");
  EXPECT_EQ(missingMonkeySegment(other), "spine");
  EXPECT_EQ(missingMonkeySegment(monkeyBody()), "");
  anatomy::Pose p;
  anatomy::Creature otherCreature;
  otherCreature.body = other;
  EXPECT_THROW(evaluateMonkeyClip(otherCreature, "walk", 0.0, p), InputError);
  EXPECT_THROW(evaluateMonkeyClip(monkey(), "fly", 0.0, p), InputError);
  EXPECT_THROW(bakeMonkeyClip(monkey(), "walk", 1), InputError);
}

}  // namespace
}  // namespace pelage::animation
