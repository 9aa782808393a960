// Cameras (scene/camera.h): view and projection, framing, the presets, orbits, and the lights'
// direction (scene/light.h).
#include "pelage/scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pelage/scene/frame.h"
#include "pelage/scene/light.h"
#include "pelage/util/error.h"
#include "support/models.h"

namespace pelage::scene {
namespace {

using test::sceneCritter;
using test::sceneFur;

// Clip-space position of a world point.
Eigen::Vector4f clip(const Camera& cam, const Eigen::Vector3f& p) {
  return cam.viewProjection() * p.homogeneous();
}

bool insideFrustum(const Camera& cam, const Eigen::Vector3f& p) {
  const Eigen::Vector4f c = clip(cam, p);
  return c.w() > 0 && std::abs(c.x()) <= c.w() && std::abs(c.y()) <= c.w() &&
         std::abs(c.z()) <= c.w();
}

FrameState restFrame() {
  FrameState f;
  evaluateFrame(sceneCritter(), anatomy::restPose(sceneCritter().body), f);
  return f;
}

TEST(Camera, ViewPutsTheEyeAtTheOriginLookingDownMinusZ) {
  Camera cam;
  cam.eye = {1.0f, 2.0f, 3.0f};
  cam.target = {-1.0f, 0.5f, 2.0f};
  const Eigen::Matrix4f v = cam.view();
  EXPECT_TRUE((v * cam.eye.homogeneous()).isApprox(Eigen::Vector4f(0, 0, 0, 1), 1e-5f));
  const Eigen::Vector4f t = v * cam.target.homogeneous();
  EXPECT_NEAR(t.x(), 0.0f, 1e-5f);
  EXPECT_NEAR(t.y(), 0.0f, 1e-5f);
  EXPECT_NEAR(t.z(), -(cam.target - cam.eye).norm(), 1e-5f);
  // World up (+Z) points up on the screen: a point above the target has eye-space y > 0.
  EXPECT_GT((v * (cam.target + Eigen::Vector3f::UnitZ() * 0.1f).homogeneous()).y(), 0.0f);
  // The rotation part is orthonormal.
  EXPECT_TRUE((v.block<3, 3>(0, 0) * v.block<3, 3>(0, 0).transpose()).isIdentity(1e-5f));
}

TEST(Camera, ProjectionMapsNearAndFarToTheDepthRange) {
  Camera cam;
  cam.nearMeters = 0.5f;
  cam.farMeters = 20.0f;
  cam.width = 300;
  cam.height = 200;
  const Eigen::Matrix4f p = cam.projection();
  const Eigen::Vector4f n = p * Eigen::Vector4f(0, 0, -0.5f, 1);
  const Eigen::Vector4f f = p * Eigen::Vector4f(0, 0, -20.0f, 1);
  EXPECT_NEAR(n.z() / n.w(), -1.0f, 1e-5f);
  EXPECT_NEAR(f.z() / f.w(), 1.0f, 1e-4f);
  // A point at the top edge of the vertical field of view lands on y = 1.
  const float half = cam.fovYDegrees * 3.14159265f / 360.0f;
  const Eigen::Vector4f top = p * Eigen::Vector4f(0, std::tan(half) * 2.0f, -2.0f, 1);
  EXPECT_NEAR(top.y() / top.w(), 1.0f, 1e-5f);
  // ... and the aspect ratio widens x.
  const Eigen::Vector4f right = p * Eigen::Vector4f(std::tan(half) * 2.0f * 1.5f, 0, -2.0f, 1);
  EXPECT_NEAR(right.x() / right.w(), 1.0f, 1e-5f);
}

TEST(Framing, TheCritterFacesPlusXAndTurningItTurnsForward) {
  const Model& m = sceneCritter();
  const FrameState f = restFrame();
  const Framing fr = framingOf(m, f, 0.0f);
  EXPECT_GT(fr.forward.x(), 0.95f);
  EXPECT_NEAR(fr.forward.z(), 0.0f, 1e-6f);
  // Every vertex inside the bounding sphere and the box.
  for (const Eigen::Vector3f& p : f.skin.positions) {
    EXPECT_LE((p - fr.center).norm(), fr.radius * (1 + 1e-5f));
    EXPECT_TRUE(fr.bounds.contains(p));
  }
  // The face region sits at the head end, much smaller than the body.
  EXPECT_GT(fr.faceCenter.x(), fr.center.x() + 0.1f);
  EXPECT_LT(fr.faceRadius, fr.radius * 0.3f);
  // Turn the whole critter by 90 degrees about Z: it faces +Y.
  anatomy::Pose pose = anatomy::restPose(m.body);
  const Eigen::Quaternionf q(Eigen::AngleAxisf(3.14159265f / 2.0f, Eigen::Vector3f::UnitZ()));
  pose.local[0].rotation = q * pose.local[0].rotation;
  pose.local[0].translation = q * pose.local[0].translation;
  FrameState turned;
  evaluateFrame(m, pose, turned);
  EXPECT_GT(framingOf(m, turned, 0.0f).forward.y(), 0.95f);
  // Hair length pads the bounds.
  const Framing padded = framingOf(m, f, 0.02f);
  EXPECT_NEAR(padded.radius, fr.radius + 0.02f, 1e-5f);
  EXPECT_NEAR(padded.bounds.max().z(), fr.bounds.max().z() + 0.02f, 1e-5f);
}

TEST(PresetCamera, EveryPresetFramesTheCreature) {
  const Model& m = sceneCritter();
  const FrameState f = restFrame();
  const float hair = maxHairLength(m, sceneFur().params);
  ASSERT_GT(hair, 0.005f);
  const Framing fr = framingOf(m, f, hair);
  const std::int32_t* region = m.skin.regions();
  int face = -1;
  for (std::size_t r = 0; r < m.skin.regionNames.size(); ++r)
    if (m.skin.regionNames[r] == "face") face = static_cast<int>(r);
  ASSERT_GE(face, 0);
  for (const auto& [w, h] : {std::pair{900, 900}, std::pair{1920, 1080}, std::pair{400, 800}}) {
    for (CameraPreset preset : {CameraPreset::Front, CameraPreset::Side, CameraPreset::ThreeQuarter,
                                CameraPreset::Face, CameraPreset::Follow}) {
      SCOPED_TRACE(testing::Message() << cameraPresetName(preset) << " " << w << "x" << h);
      const Camera cam = presetCamera(fr, preset, w, h);
      EXPECT_EQ(cam.width, w);
      EXPECT_EQ(cam.height, h);
      const bool faceOnly = preset == CameraPreset::Face;
      double minX = 1, maxX = -1, minY = 1, maxY = -1;
      for (std::size_t v = 0; v < f.skin.positions.size(); ++v) {
        if (faceOnly && region[v] != face) continue;
        // The vertex and the hair-length ball around it are in the frustum.
        const Eigen::Vector3f& p = f.skin.positions[v];
        for (int axis = 0; axis < 7; ++axis) {
          const Eigen::Vector3f q = axis == 6
                                        ? p
                                        : Eigen::Vector3f(p + (axis % 2 ? -hair : hair) *
                                                                  Eigen::Vector3f::Unit(axis / 2));
          ASSERT_TRUE(insideFrustum(cam, q)) << v;
        }
        const Eigen::Vector4f c = clip(cam, p);
        minX = std::min<double>(minX, c.x() / c.w());
        maxX = std::max<double>(maxX, c.x() / c.w());
        minY = std::min<double>(minY, c.y() / c.w());
        maxY = std::max<double>(maxY, c.y() / c.w());
      }
      // Framed, not lost in the distance: the creature spans at least a fifth of the view (the
      // bounding sphere is conservative for a long body seen end-on, as from the front).
      EXPECT_GT(std::max(maxX - minX, maxY - minY), 0.4);
    }
  }
  // Face close-up: the camera is much closer than for the whole body.
  const Camera whole = presetCamera(fr, CameraPreset::ThreeQuarter, 900, 900);
  const Camera faceCam = presetCamera(fr, CameraPreset::Face, 900, 900);
  EXPECT_LT(faceCam.distance(), whole.distance() * 0.4f);
  // Front looks at the face side (+X), side from the critter's left (+Y).
  EXPECT_GT(presetCamera(fr, CameraPreset::Front, 900, 900).eye.x(), fr.center.x() + fr.radius);
  EXPECT_GT(presetCamera(fr, CameraPreset::Side, 900, 900).eye.y(), fr.center.y() + fr.radius);
  // Follow looks at the root segment from behind (-X) and above.
  const Camera follow = presetCamera(fr, CameraPreset::Follow, 900, 900);
  EXPECT_TRUE(follow.target.isApprox(fr.rootPosition));
  EXPECT_LT(follow.eye.x(), fr.rootPosition.x());
  EXPECT_GT(follow.eye.z(), fr.rootPosition.z());
}

TEST(Orbit, RoundTripsThroughACamera) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 100; ++i) {
    Orbit o;
    o.target = Eigen::Vector3f(u(rng), u(rng), u(rng));
    o.azimuthDegrees = 179.0f * u(rng);
    o.elevationDegrees = 85.0f * u(rng);
    o.distanceMeters = 2.0f + u(rng);
    const Orbit back = orbitOf(orbitCamera(o, 100, 100));
    EXPECT_TRUE(back.target.isApprox(o.target));
    EXPECT_NEAR(back.azimuthDegrees, o.azimuthDegrees, 1e-2f);
    EXPECT_NEAR(back.elevationDegrees, o.elevationDegrees, 1e-2f);
    EXPECT_NEAR(back.distanceMeters, o.distanceMeters, 1e-4f);
  }
}

TEST(Names, CameraPresetsParseAndRejectUnknownNames) {
  for (CameraPreset p : {CameraPreset::Front, CameraPreset::Side, CameraPreset::ThreeQuarter,
                         CameraPreset::Face, CameraPreset::Follow})
    EXPECT_EQ(parseCameraPreset(cameraPresetName(p)), p);
  try {
    parseCameraPreset("top");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("three-quarter"), std::string::npos);
  }
}

TEST(LightDirection, IsAUnitVectorAtTheGivenAngles) {
  const Eigen::Vector3f d = lightDirection(90.0f, 30.0f);
  EXPECT_NEAR(d.norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(d.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(d.y(), std::cos(3.14159265f / 6.0f), 1e-6f);
  EXPECT_NEAR(d.z(), 0.5f, 1e-6f);
}

}  // namespace
}  // namespace pelage::scene
