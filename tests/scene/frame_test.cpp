#include "pelage/scene/frame.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pelage/animation/clip.h"
#include "pelage/util/error.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

using test::sceneCritter;
using test::sceneFur;

TEST(EvaluateFrame, RestPoseGivesTheBindSkinAndItsBounds) {
  const Model& m = sceneCritter();
  FrameState f;
  evaluateFrame(m, anatomy::restPose(m.body), f);
  ASSERT_EQ(f.skin.positions.size(), static_cast<std::size_t>(m.skin.numVertices()));
  Eigen::AlignedBox3f box;
  for (int v = 0; v < m.skin.numVertices(); ++v) {
    const Eigen::Vector3f rest = Eigen::Map<const Eigen::Vector3f>(m.skin.restPositions() + 3 * v);
    ASSERT_TRUE(f.skin.positions[static_cast<std::size_t>(v)].isApprox(rest, 1e-5f));
    box.extend(rest);
  }
  EXPECT_TRUE(f.skinBounds.min().isApprox(box.min(), 1e-5f));
  EXPECT_TRUE(f.skinBounds.max().isApprox(box.max(), 1e-5f));
  EXPECT_EQ(f.body.world.size(), static_cast<std::size_t>(m.body.size()));
}

TEST(EvaluateFrame, ATranslatedPoseMovesSkinAndBounds) {
  const Model& m = sceneCritter();
  FrameState a, b;
  evaluateFrame(m, anatomy::restPose(m.body), a);
  anatomy::Pose p = anatomy::restPose(m.body);
  p.local[0].translation += Eigen::Vector3f(0.5f, -0.25f, 1.0f);
  evaluateFrame(m, p, b);
  EXPECT_TRUE((b.skinBounds.min() - a.skinBounds.min())
                  .isApprox(Eigen::Vector3f(0.5f, -0.25f, 1.0f), 1e-4f));
  // The same FrameState reused: no stale data.
  evaluateFrame(m, anatomy::restPose(m.body), b);
  EXPECT_TRUE(b.skinBounds.min().isApprox(a.skinBounds.min()));
}

TEST(EvaluateClipFrame, SamplesTheClipThenDeforms) {
  // A clip that rolls the critter over: its root segment turns by 120 degrees about +Y in 1 s.
  Model m = sceneCritter();
  animation::Clip roll;
  roll.name = "roll";
  roll.duration = 1.0f;
  roll.loop = false;
  animation::Channel ch;
  ch.segment = 0;
  ch.path = animation::ChannelPath::Rotation;
  ch.interpolation = animation::Interpolation::Linear;
  const Eigen::Quaternionf q0 = m.body.segments[0].rest.rotation;
  const Eigen::Quaternionf q1 =
      Eigen::Quaternionf(Eigen::AngleAxisf(2.0f * 3.14159265f / 3.0f, Eigen::Vector3f::UnitY())) *
      q0;
  ch.times = {0.0f, 1.0f};
  ch.values = {q0.x(), q0.y(), q0.z(), q0.w(), q1.x(), q1.y(), q1.z(), q1.w()};
  roll.channels.push_back(ch);
  m.clips.push_back(roll);
  FrameState a, b;
  evaluateClipFrame(m, 0, 1.0, a);
  anatomy::Pose pose;
  animation::sampleClip(m.clips[0], m.body, 1.0, pose);
  evaluateFrame(m, pose, b);
  ASSERT_EQ(a.skin.positions.size(), b.skin.positions.size());
  for (std::size_t v = 0; v < a.skin.positions.size(); ++v)
    ASSERT_EQ(a.skin.positions[v], b.skin.positions[v]);
  // Rolled over: the head, 0.2 m ahead (+X) of the root at rest, is now behind and below it
  // (R_y(120 deg) (0.2, 0, 0.05) = (-0.057, 0, -0.198)).
  const int head = m.body.find("head");
  const Eigen::Vector3f root = a.body.world[0].translation();
  const Eigen::Vector3f h1 = a.body.world[static_cast<std::size_t>(head)].translation() - root;
  EXPECT_NEAR(h1.x(), -0.057f, 0.005f);
  EXPECT_NEAR(h1.z(), -0.198f, 0.005f);
  // Halfway (0.5 s): 60 degrees, (0.2, 0, 0.05) -> (0.143, 0, -0.148).
  evaluateClipFrame(m, 0, 0.5, a);
  const Eigen::Vector3f h2 = a.body.world[static_cast<std::size_t>(head)].translation() - root;
  EXPECT_NEAR(h2.x(), 0.143f, 0.005f);
  EXPECT_NEAR(h2.z(), -0.148f, 0.005f);
  EXPECT_THROW(evaluateClipFrame(m, 1, 0.0, a), InternalError);
}

TEST(GrowFur, GenerationsAreUniqueAndRootParametersAreDetected) {
  const Model& m = sceneCritter();
  fur::FurParams p = sceneFur().params;
  p.setHairCount(1000);
  const Fur a = growFur(m, p);
  const Fur b = growFur(m, p);
  EXPECT_NE(a.generation, b.generation);
  EXPECT_NE(a.generation, 0u);
  EXPECT_EQ(a.roots.total(), b.roots.total());
  fur::FurParams q = p;
  q.coats[0].stiffness = 0.9f;
  q.lengthScale = 2.0f;
  q.coats[1].style = fur::HairStyle::Tube;
  EXPECT_FALSE(rootsDiffer(p, q));
  for (auto change :
       {+[](fur::FurParams& x) { x.hairs += 1; }, +[](fur::FurParams& x) { x.seed += 1; },
        +[](fur::FurParams& x) { x.undercoatShare = 0.9f; },
        +[](fur::FurParams& x) { x.densityPerM2 = 1e6; }}) {
    fur::FurParams r = p;
    change(r);
    EXPECT_TRUE(rootsDiffer(p, r));
  }
  fur::FurParams bad = p;
  bad.coats[0].stiffness = 2.0f;
  try {
    growFur(m, bad, "my.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("my.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("stiffness"), std::string::npos);
  }
}

TEST(EvaluateFur, EveryHairLiesWithinTheLongestHairOfItsRoot) {
  const Model& m = sceneCritter();
  FrameState f;
  evaluateFrame(m, anatomy::restPose(m.body), f);
  fur::FurParams p = sceneFur().params;
  p.culling.enabled = false;
  p.lengthRegion.shape = fur::LengthRegion::Shape::Sphere;
  p.lengthRegion.center = Eigen::Vector3f(0.25f, 0.0f, 0.38f);  // the critter's head
  p.lengthRegion.radius = 0.1f;
  p.lengthRegion.scale = 3.0f;
  const Fur fur = growFur(m, p);
  evaluateFur(m, fur, fur::FurView{}, true, f);
  const float longest = maxHairLength(m, fur.params);
  float seen = 0.0f;
  for (const fur::HairBuffers& hb : f.fur.coats) {
    ASSERT_GT(hb.drawn, 0);
    const int P = hb.layout.pointsPerHair();
    for (std::int64_t h = 0; h < hb.drawn; ++h) {
      const float* q = hb.positions.data() + h * P * 3;
      const Eigen::Vector3f root(q[0], q[1], q[2]);
      for (int i = 1; i < P; ++i)
        seen =
            std::max(seen, (Eigen::Vector3f(q[3 * i], q[3 * i + 1], q[3 * i + 2]) - root).norm());
    }
  }
  EXPECT_LE(seen, longest * 1.0001f);
  EXPECT_GT(seen, longest * 0.5f);  // the bound is not absurdly loose
}

// A camera looking at `center` from `distance` along `dir`, with the preset's reference field of
// view and image height unless others are given.
Camera cameraAt(const Fur& fur, const Eigen::Vector3f& center, const Eigen::Vector3f& dir,
                float distance, float fovY = 0.0f, int height = 0) {
  Camera c;
  c.target = center;
  c.eye = center + dir * distance;
  c.fovYDegrees = fovY > 0.0f ? fovY : fur.params.culling.fovYDegrees;
  c.height = c.width = height > 0 ? height : fur.params.culling.referenceHeight;
  return c;
}

// Van Gelder & Wilhelms 1997, sec. 3.3: "when the viewing distance doubles, the number of hairs
// drawn decreases by a factor of two" -- and the count-only path (GPU source) agrees with the CPU.
TEST(EvaluateFur, DoublingTheDistanceHalvesTheDrawnHairs) {
  const Model& m = sceneCritter();
  const Fur& fur = sceneFur();
  FrameState f;
  evaluateFrame(m, anatomy::restPose(m.body), f);
  const Eigen::Vector3f center = fur::creatureCenter(f.skin);
  const float ref = fur::referenceDistance(fur.params);
  const Eigen::Vector3f dir = Eigen::Vector3f(1, 1, 0.5f).normalized();
  auto drawnAt = [&](float distance, bool cpu) {
    evaluateFur(m, fur, cameraAt(fur, center, dir, distance), cpu, f);
    EXPECT_NEAR(f.cullFactor, std::max(1.0f, distance / ref), 1e-4f * distance / ref);
    return f.drawnHairs[0] + f.drawnHairs[1];
  };
  // Closer than the reference distance: everything.
  EXPECT_EQ(drawnAt(ref * 0.5f, false), fur.roots.total());
  for (float d : {2.0f * ref, 3.0f * ref, 5.0f * ref}) {
    const std::int64_t near = drawnAt(d, false), far = drawnAt(2.0f * d, false);
    EXPECT_EQ(near, drawnAt(d, true));
    EXPECT_EQ(far, drawnAt(2.0f * d, true));
    const double ratio = static_cast<double>(near) / static_cast<double>(far);
    EXPECT_NEAR(ratio, 2.0, 0.06) << d / ref;
    // 1/c of the hairs on average (random rounding is unbiased).
    EXPECT_NEAR(static_cast<double>(near) / static_cast<double>(fur.roots.total()), ref / d, 0.02);
  }
  // Culling off: every hair at any distance.
  Fur all = fur;
  all.params.culling.enabled = false;
  evaluateFur(m, all, cameraAt(fur, center, dir, 100.0f * ref), false, f);
  EXPECT_EQ(f.drawnHairs[0] + f.drawnHairs[1], fur.roots.total());
  EXPECT_EQ(f.cullFactor, 1.0f);
}

// The zoom factor is the creature's scale on screen: four times the distance with the field of
// view narrowed so that the creature keeps its size on screen draws the same hairs; an image twice
// as high draws twice the hairs (while c > 1).
TEST(EvaluateFur, TheCreaturesSizeOnScreenSetsTheDrawnHairs) {
  const Model& m = sceneCritter();
  const Fur& fur = sceneFur();
  FrameState f;
  evaluateFrame(m, anatomy::restPose(m.body), f);
  const Eigen::Vector3f center = fur::creatureCenter(f.skin);
  const float ref = fur::referenceDistance(fur.params);
  const Eigen::Vector3f dir = Eigen::Vector3f(-1, 2, 0.3f).normalized();
  const float fov = 40.0f;
  auto narrowed = [&](float factor) {  // the field of view seeing 1/factor of fov's height
    return 2.0f * std::atan(std::tan(0.5f * fov * 3.14159265f / 180.0f) / factor) * 180.0f /
           3.14159265f;
  };
  for (const float d : {3.0f * ref, 6.0f * ref}) {
    SCOPED_TRACE(d / ref);
    evaluateFur(m, fur, cameraAt(fur, center, dir, d, fov, 720), false, f);
    const float c = f.cullFactor;
    const std::int64_t drawn = f.drawnHairs[0] + f.drawnHairs[1];
    EXPECT_GT(c, 1.5f);
    for (const float k : {4.0f, 8.0f}) {
      evaluateFur(m, fur, cameraAt(fur, center, dir, k * d, narrowed(k), 720), false, f);
      EXPECT_NEAR(f.cullFactor, c, 1e-4f * c);
      EXPECT_NEAR(static_cast<double>(f.drawnHairs[0] + f.drawnHairs[1]),
                  static_cast<double>(drawn), 2e-3 * static_cast<double>(drawn));
    }
    evaluateFur(m, fur, cameraAt(fur, center, dir, d, fov, 1440), false, f);
    EXPECT_NEAR(f.cullFactor, c / 2.0f, 1e-4f * c);
    EXPECT_NEAR(static_cast<double>(f.drawnHairs[0] + f.drawnHairs[1]) / drawn, 2.0, 0.05);
  }
}

}  // namespace
}  // namespace pelage::scene
