// The frame owner (scene/playback.h), tested directly: a clip's frame and the still pose pose the
// skin the frame functions give, a frame reached out of order with dynamics equals a whole run's
// bit for bit (the pre-roll), the GPU source counts the hairs the CPU draws, a playback's limits
// name their fields, a fur that clumps runs on either source (on the CPU with dynamics), and a
// stop asked for ends a frame before it is posed.
#include "pelage/scene/playback.h"

#include <gtest/gtest.h>

#include <cstring>

#include "pelage/anatomy/pose.h"
#include "pelage/animation/clip.h"
#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

using test::wagCritter;
using test::wagFur;

bool sameSkin(const FrameState& a, const FrameState& b) {
  if (a.skin.positions.size() != b.skin.positions.size()) return false;
  for (std::size_t i = 0; i < a.skin.positions.size(); ++i)
    if (a.skin.positions[i] != b.skin.positions[i] || a.skin.normals[i] != b.skin.normals[i])
      return false;
  return true;
}

bool sameHairs(const fur::FurFrame& a, const fur::FurFrame& b) {
  if (a.drawn() != b.drawn() || a.positions.size() != b.positions.size()) return false;
  return std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(float)) ==
         0;
}

TEST(Playback, AClipFrameIsTheClipAtItsTime) {
  PlaybackOptions o;
  o.clip = 0;
  o.clock.fps = 12.0;
  o.clock.startSeconds = 0.25;
  Playback p(wagCritter(), wagFur(), o);
  FrameState expected;
  for (const int f : {0, 5, 3, 17}) {  // any order, past the clip's end too (it loops)
    p.poseFrame(f);
    evaluateClipFrame(wagCritter(), 0, 0.25 + f / 12.0, expected);
    EXPECT_TRUE(sameSkin(p.state(), expected)) << "frame " << f;
  }
  // Frames differ from one another: the critter moves.
  p.poseFrame(0);
  evaluateClipFrame(wagCritter(), 0, 0.25 + 6 / 12.0, expected);
  EXPECT_FALSE(sameSkin(p.state(), expected));
}

TEST(Playback, APlayedPoseIsItsClipBlendOrStillPoseTurnedAboutTheFirstCentre) {
  // The viewer's poses (posePlayed): a clip at any time, a cross-fade, the still pose, each as the
  // animation module samples it; the turntable turns the skin rigidly about +Z through the centre
  // of the first pose played.
  const Model& m = wagCritter();
  Playback p(m, wagFur(), PlaybackOptions{});
  PlayedPose played;
  played.clip = 0;
  played.seconds = 0.4;
  p.posePlayed(played, 1.0 / 30.0);
  const Framing first = p.framing();
  FrameState expected;
  evaluateClipFrame(m, 0, 0.4, expected);
  EXPECT_TRUE(sameSkin(p.state(), expected));

  played.fromClip = 0;
  played.fromSeconds = 0.1;
  played.fadeWeight = 0.3f;
  p.posePlayed(played, 1.0 / 30.0);
  anatomy::Pose blended, scratch;
  animation::sampleBlend(m.clips[0], 0.1, m.clips[0], 0.4, 0.3f, m.body, scratch, blended);
  evaluateFrame(m, blended, expected);
  EXPECT_TRUE(sameSkin(p.state(), expected));
  FrameState clipOnly;
  evaluateClipFrame(m, 0, 0.4, clipOnly);
  EXPECT_FALSE(sameSkin(p.state(), clipOnly));  // the fade shows

  played = PlayedPose{};  // the still pose (the rest pose here)
  p.posePlayed(played, 1.0 / 30.0);
  evaluateFrame(m, anatomy::restPose(m.body), expected);
  EXPECT_TRUE(sameSkin(p.state(), expected));

  played.turnDegrees = 450.0;  // a quarter turn past a whole one
  p.posePlayed(played, 1.0 / 30.0);
  const Eigen::Vector3f pivot(first.center.x(), first.center.y(), 0.0f);
  const Eigen::Matrix3f r =
      Eigen::AngleAxisf(0.5f * 3.14159265f, Eigen::Vector3f::UnitZ()).matrix();
  double worst = 0.0;
  for (std::size_t v = 0; v < expected.skin.positions.size(); ++v)
    worst = std::max(worst, static_cast<double>((p.state().skin.positions[v] -
                                                 (r * (expected.skin.positions[v] - pivot) + pivot))
                                                    .norm()));
  EXPECT_LT(worst, 2e-6);
  EXPECT_GT((p.state().skin.positions[0] - expected.skin.positions[0]).norm(), 1e-3f);
}

TEST(Playback, ASequenceFramesCameraIsItsRigsOnThatFrame) {
  PlaybackOptions o;
  o.clip = 0;
  Playback p(wagCritter(), wagFur(), o);
  CameraRig rig;
  rig.preset = CameraPreset::Side;
  rig.track = true;
  const Camera c = p.sequenceCamera(9, rig, 320, 200);
  const Camera expected = rigCamera(rig, p.firstFraming(), p.framing(), 9, 320, 200);
  EXPECT_EQ(c.eye, expected.eye);
  EXPECT_EQ(c.target, expected.target);
  FrameState f9;
  evaluateClipFrame(wagCritter(), 0, 9 / 30.0, f9);
  EXPECT_TRUE(sameSkin(p.state(), f9));  // posed on frame 9
}

TEST(Playback, TheStillPoseIsTheSameEveryFrame) {
  PlaybackOptions o;  // clip -1
  Playback p(wagCritter(), wagFur(), o);
  FrameState rest;
  evaluateFrame(wagCritter(), anatomy::restPose(wagCritter().body), rest);
  for (const int f : {0, 7, 100}) {
    p.poseFrame(f);
    EXPECT_TRUE(sameSkin(p.state(), rest)) << "frame " << f;
  }
  EXPECT_EQ(wholeClip(wagCritter(), -1, 30.0).count(), 1);
  EXPECT_EQ(wholeClip(wagCritter(), 0, 12.0).last, 12);  // 1 s at 12 frames/s: 0 to 12
}

TEST(Playback, AFrameReachedOutOfOrderEqualsAWholeRunWithDynamics) {
  PlaybackOptions o;
  o.clip = 0;
  o.clock.fps = 24.0;
  o.hairSource = HairSource::Cpu;
  o.dynamics = true;
  Playback whole(wagCritter(), wagFur(), o);
  for (int f = 0; f <= 9; ++f) {
    whole.poseFrame(f);
    whole.evaluateFur(fur::FurView{});
  }
  Playback jump(wagCritter(), wagFur(), o);
  jump.poseFrame(9);  // pre-rolled through frames 0..8
  jump.evaluateFur(fur::FurView{});
  ASSERT_GT(whole.state().fur.drawn(), 0);
  EXPECT_TRUE(sameHairs(whole.state().fur, jump.state().fur));
  // And the springs matter: the quasi-static hairs of frame 9 differ.
  PlaybackOptions still = o;
  still.dynamics = false;
  Playback quasi(wagCritter(), wagFur(), still);
  quasi.poseFrame(9);
  quasi.evaluateFur(fur::FurView{});
  EXPECT_FALSE(sameHairs(whole.state().fur, quasi.state().fur));
}

TEST(Playback, TheGpuSourceCountsTheHairsTheCpuDraws) {
  CameraRig rig;
  rig.preset = CameraPreset::Side;
  std::int64_t total[2] = {0, 0};  // near, far
  for (const bool far : {false, true}) {
    std::array<std::int64_t, 2> counts[2];
    for (const HairSource source : {HairSource::Cpu, HairSource::Gpu}) {
      PlaybackOptions o;
      o.clip = 0;
      o.hairSource = source;
      Playback p(wagCritter(), wagFur(), o);
      // A far, narrow view culls (sec. 3.3); the near one draws every hair.
      rig.fovYDegrees = far ? 2.0f : kDefaultFovYDegrees;
      const DrawList& list =
          p.sequenceFrame(4, rig, far ? 64 : 640, far ? 48 : 480, Light{}, DrawOptions{});
      EXPECT_EQ(list.fur.empty(), false);
      counts[source == HairSource::Gpu] = p.state().drawnHairs;
      EXPECT_EQ(list.drawnHairs(), p.state().drawnHairs[0] + p.state().drawnHairs[1]);
    }
    EXPECT_EQ(counts[0], counts[1]) << (far ? "far" : "near");
    total[far] = counts[0][0] + counts[0][1];
  }
  EXPECT_EQ(total[0], wagFur().roots.total());  // near: every hair
  EXPECT_LT(total[1], total[0] / 2);            // far: culled
}

TEST(Playback, LimitsNameTheirFields) {
  const auto fieldOf = [](auto f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(fieldOf([] { validateImageSize(15, 100); }), "size");
  EXPECT_EQ(fieldOf([] { validateImageSize(kMaxImageSide, kMinImageSide); }), "(accepted)");
  EXPECT_EQ(fieldOf([] { validateFov(179.0); }), "fov");
  EXPECT_EQ(fieldOf([] { validateColor(Eigen::Vector3f(0, 1.5f, 0), "skin color"); }),
            "skin color");
  PlaybackOptions o;  // the clock's limits (tests/scene/clock_test.cpp) hold for a playback
  o.clock.fps = 0.0;
  EXPECT_THROW(Playback(wagCritter(), wagFur(), o), InputError);
  o.clock.fps = 30.0;
  o.clock.startSeconds = -1.0;
  EXPECT_THROW(Playback(wagCritter(), wagFur(), o), InputError);
}

TEST(Playback, ClumpingRunsOnTheAskedSourceAndWithDynamicsOnTheCpu) {
  // A fur that clumps runs on the GPU when asked: the frame then carries its clump centres' strand
  // points (what the shader pulls the clumped hairs toward), the CPU frame's bit for bit. With
  // dynamics the fur runs on the CPU and its dynamic hairs clump (fur/dynamics_test.cpp: how).
  fur::FurParams p = wagFur().params;
  p.coats[0].clump = {.density = 2.0f, .strength = 0.8f, .shape = 1.0f, .radiusMm = 10.0f};
  const Fur clumped = growFur(wagCritter(), p, "test");
  ASSERT_FALSE(clumped.roots.coats[0].clumpCentres.empty());
  PlaybackOptions o;
  o.clip = 0;
  o.hairSource = HairSource::Gpu;
  EXPECT_EQ(Playback(wagCritter(), wagFur(), o).hairSource(), HairSource::Gpu);
  Playback gpu(wagCritter(), clumped, o);
  EXPECT_EQ(gpu.hairSource(), HairSource::Gpu);
  o.hairSource = HairSource::Cpu;
  Playback cpu(wagCritter(), clumped, o);
  Playback plain(wagCritter(), wagFur(), o);
  for (Playback* pb : {&plain, &cpu, &gpu}) {
    pb->poseFrame(3);
    pb->evaluateFur(fur::FurView{});
  }
  ASSERT_FALSE(gpu.state().cpuFur);
  ASSERT_TRUE(cpu.state().cpuFur);
  const std::vector<float>& centres = gpu.state().furWorkspace.clumpCentres[0];
  EXPECT_EQ(centres.size(), clumped.roots.coats[0].clumpCentres.size() * 3 *
                                static_cast<std::size_t>(fur::hairLayout(p.coats[0]).strandPoints));
  EXPECT_EQ(centres, cpu.state().furWorkspace.clumpCentres[0]);
  EXPECT_EQ(gpu.state().drawnHairs, cpu.state().drawnHairs);
  // The CPU's clumped hairs differ from the unclumped fur's.
  ASSERT_EQ(plain.state().fur.drawn(), cpu.state().fur.drawn());
  EXPECT_FALSE(sameHairs(plain.state().fur, cpu.state().fur));
  o.hairSource = HairSource::Gpu;  // asked, but dynamics runs on the CPU
  o.dynamics = true;
  Playback dynamic(wagCritter(), clumped, o);
  EXPECT_EQ(dynamic.hairSource(), HairSource::Cpu);
  Playback dynamicPlain(wagCritter(), wagFur(), o);
  for (Playback* pb : {&dynamic, &dynamicPlain}) {
    pb->poseFrame(3);
    pb->evaluateFur(fur::FurView{});
  }
  ASSERT_TRUE(dynamic.state().cpuFur);
  ASSERT_EQ(dynamic.state().fur.drawn(), dynamicPlain.state().fur.drawn());
  EXPECT_FALSE(sameHairs(dynamic.state().fur, dynamicPlain.state().fur));
}

void stopNow() {
  throw Interrupted(0);
}

TEST(Playback, AStopAskedForEndsTheNextFrame) {
  PlaybackOptions o;
  o.clip = 0;
  Playback p(wagCritter(), wagFur(), o);
  setInterruptPoll(stopNow);
  EXPECT_THROW(p.poseFrame(3), Interrupted);
  setInterruptPoll(nullptr);
  EXPECT_NO_THROW(p.poseFrame(3));
}

}  // namespace
}  // namespace pelage::scene
