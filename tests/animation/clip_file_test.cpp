// The JSON clip format: keys relative to the rest pose, the three interpolations, periodic cubic
// curves, and clear errors naming the file and the field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "pelage/anatomy/body.h"
#include "pelage/animation/clip_file.h"
#include "pelage/util/error.h"
#include "support/files.h"

namespace pelage::animation {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;

anatomy::Body body() {
  anatomy::SegmentSpec root, arm;
  root.name = "pelvis";
  root.rest.translation = Eigen::Vector3f(0, 0, 0.3f);
  arm.name = "arm";
  arm.parent = "pelvis";
  arm.rest.translation = Eigen::Vector3f(0.1f, 0, 0);
  arm.rest.rotation = Eigen::Quaternionf(Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitZ()));
  arm.rest.scale = Eigen::Vector3f(1, 2, 1);
  return anatomy::makeBody({root, arm}, "test");
}

Eigen::Quaternionf aa(double deg, const Eigen::Vector3f& axis) {
  return Eigen::Quaternionf(
      Eigen::AngleAxisf(static_cast<float>(deg * kPi / 180.0), axis.normalized()));
}

const char* kWave = R"({
  "name": "wave", "duration": 2.0,
  "rootMotion": { "segment": "pelvis", "translate": [0.5, 0, 0] },
  "channels": [
    { "segment": "arm", "path": "rotate", "interpolation": "linear",
      "keys": [ { "time": 0, "axis": [0, 1, 0], "degrees": 0 }, { "time": 1, "axis": [0, 1, 0], "degrees": 60 } ] },
    { "segment": "pelvis", "path": "translate", "interpolation": "step",
      "keys": [ { "time": 0, "value": [0, 0, 0] }, { "time": 1, "value": [0, 0, 0.1] } ] },
    { "segment": "arm", "path": "scale", "keys": [ { "time": 0, "value": [1, 1, 1] }, { "time": 2, "value": [3, 1, 1] } ] }
  ] })";

TEST(ClipFile, KeysAreRelativeToTheRestPose) {
  const anatomy::Body b = body();
  const Clip clip = parseClip(b, kWave, "wave.json");
  EXPECT_EQ(clip.name, "wave");
  EXPECT_TRUE(clip.loop);
  EXPECT_FLOAT_EQ(clip.duration, 2.0f);
  EXPECT_EQ(clip.rootMotionSegment, 0);
  anatomy::Pose p;
  sampleClip(clip, b, 0.5, p);
  // rotate: rest * R(axis, degrees), linear in the angle.
  EXPECT_NEAR(p.local[1].rotation.angularDistance(b.segments[1].rest.rotation *
                                                  aa(30, Eigen::Vector3f::UnitY())),
              0, 1e-5);
  // scale: multiplies the rest scale; 0.5 s of 2 s -> factor 1.5 in x.
  EXPECT_TRUE(p.local[1].scale.isApprox(Eigen::Vector3f(1.5f, 2.0f, 1.0f)));
  // step translation: still the first key.
  EXPECT_TRUE(p.local[0].translation.isApprox(Eigen::Vector3f(0, 0, 0.3f)));
  sampleClip(clip, b, 1.5, p);
  EXPECT_TRUE(p.local[0].translation.isApprox(Eigen::Vector3f(0, 0, 0.4f)));
  // Second cycle: root motion added once.
  sampleClip(clip, b, 3.5, p);
  EXPECT_TRUE(p.local[0].translation.isApprox(Eigen::Vector3f(0.5f, 0, 0.4f)));
}

// A periodic cubic curve passes through its keys and has the same slope on both sides of the loop.
TEST(ClipFile, CubicCurvesPassThroughKeysAndLoopSmoothly) {
  const anatomy::Body b = body();
  const Clip clip = parseClip(
      b, R"({ "channels": [ { "segment": "arm", "path": "rotate", "interpolation": "cubic",
      "keys": [ { "time": 0, "axis": [0, 0, 1], "degrees": 0 }, { "time": 0.5, "axis": [0, 0, 1], "degrees": 40 },
                { "time": 1.0, "axis": [0, 0, 1], "degrees": 10 }, { "time": 2.0, "axis": [0, 0, 1], "degrees": 0 } ] } ] })",
      "cubic.json");
  EXPECT_EQ(clip.name, "cubic");
  const Eigen::Quaternionf rest = b.segments[1].rest.rotation;
  anatomy::Pose p;
  const double keys[][2] = {{0, 0}, {0.5, 40}, {1.0, 10}};
  for (const auto& k : keys) {
    sampleClip(clip, b, k[0], p);
    EXPECT_NEAR(p.local[1].rotation.angularDistance(rest * aa(k[1], Eigen::Vector3f::UnitZ())), 0,
                1e-5)
        << k[0];
  }
  // Signed angle about z relative to rest.
  auto angle = [&](double t) {
    sampleClip(clip, b, t, p);
    const Eigen::Quaternionf d = rest.conjugate() * p.local[1].rotation;
    return 2.0 * std::atan2(static_cast<double>(d.z()), static_cast<double>(d.w())) * 180.0 / kPi;
  };
  const double h = 2e-4;
  const double slopeBefore = (angle(2.0 - h) - angle(2.0 - 2 * h)) / h;
  const double slopeAfter = (angle(2.0 + 2 * h) - angle(2.0 + h)) / h;
  EXPECT_GT(std::abs(slopeAfter), 10.0);  // the curve is moving at the loop point
  EXPECT_NEAR(slopeBefore, slopeAfter, 0.02 * std::abs(slopeAfter) + 0.3);
}

TEST(ClipFile, LoadsFromAFileNamedAfterIt) {
  test::TempDir dir;
  test::writeText(dir.file("swing.json"),
                  R"({ "loop": false, "channels": [ { "segment": "arm", "path": "translate",
      "keys": [ { "time": 0, "value": [0, 0, 0] }, { "time": 1, "value": [0, 0, 1] } ] } ] })");
  const Clip clip = loadClip(body(), dir.file("swing.json"));
  EXPECT_EQ(clip.name, "swing");
  EXPECT_FALSE(clip.loop);
  EXPECT_FLOAT_EQ(clip.duration, 1.0f);
}

struct Bad {
  const char* name;
  const char* text;
  const char* expect;
};

// gtest names the case by this (not its bytes) in test names and failures.
void PrintTo(const Bad& c, std::ostream* os) {
  *os << c.name;
}

class ClipFileErrors : public ::testing::TestWithParam<Bad> {};

TEST_P(ClipFileErrors, NameTheFileAndTheField) {
  const Bad& c = GetParam();
  try {
    parseClip(body(), c.text, "bad_clip.json");
    FAIL() << "accepted: " << c.text;
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad_clip.json"));
    EXPECT_THAT(e.what(), HasSubstr(c.expect));
  }
}

#define KEY0 R"({ "time": 0, "axis": [0, 1, 0], "degrees": 0 })"
INSTANTIATE_TEST_SUITE_P(
    All, ClipFileErrors,
    ::testing::Values(
        Bad{"syntax", R"({ "channels": [ )", "malformed JSON"},
        Bad{"no channels", R"({ "channels": [] })", "at least one channel"},
        Bad{"unknown segment",
            R"({ "channels": [ { "segment": "tail", "path": "rotate", "keys": [)" KEY0 R"(] } ] })",
            "unknown segment 'tail'"},
        Bad{"unknown path",
            R"({ "channels": [ { "segment": "arm", "path": "twist", "keys": [)" KEY0 R"(] } ] })",
            "unknown path 'twist'"},
        Bad{"unknown interpolation",
            R"({ "channels": [ { "segment": "arm", "path": "rotate", "interpolation": "bezier", "keys": [)" KEY0
            R"(] } ] })",
            "unknown interpolation 'bezier'"},
        Bad{"no keys", R"({ "channels": [ { "segment": "arm", "path": "rotate", "keys": [] } ] })",
            "at least one key"},
        Bad{"times not increasing",
            R"({ "channels": [ { "segment": "arm", "path": "rotate", "keys": [)" KEY0 "," KEY0
            R"(] } ] })",
            "channels[0].keys[1].time"},
        Bad{"negative time",
            R"({ "channels": [ { "segment": "arm", "path": "rotate", "keys": [ { "time": -1, "axis": [0, 1, 0], "degrees": 0 } ] } ] })",
            "out of range"},
        Bad{"zero axis",
            R"({ "channels": [ { "segment": "arm", "path": "rotate", "keys": [ { "time": 0, "axis": [0, 0, 0], "degrees": 5 } ] } ] })",
            "axis must be non-zero"},
        Bad{"zero scale",
            R"({ "channels": [ { "segment": "arm", "path": "scale", "keys": [ { "time": 0, "value": [1, 0, 1] } ] } ] })",
            "scale factors must lie in (0, 1000]"},
        Bad{"duplicate channel",
            R"({ "channels": [ { "segment": "arm", "path": "rotate", "keys": [)" KEY0 R"(] },
                               { "segment": "arm", "path": "rotate", "keys": [)" KEY0 R"(] } ] })",
            "already has a 'rotate' channel"},
        Bad{"short duration",
            R"({ "duration": 0.5, "channels": [ { "segment": "arm", "path": "rotate", "keys": [)" KEY0
            R"(, { "time": 1, "axis": [0, 1, 0], "degrees": 3 } ] } ] })",
            "shorter than the last key time"},
        Bad{"typo", R"({ "chanels": [] })", "unknown field 'chanels'"},
        Bad{"root motion segment",
            R"({ "rootMotion": { "segment": "nope", "translate": [1, 0, 0] }, "channels": [ { "segment": "arm", "path": "rotate", "keys": [)" KEY0
            R"(] } ] })",
            "unknown segment 'nope'"}),
    [](const ::testing::TestParamInfo<Bad>& param) {
      std::string n = param.param.name;
      for (char& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

TEST(ClipFile, MissingFileIsAnInputError) {
  EXPECT_THROW(loadClip(body(), "/nonexistent/clip.json"), InputError);
}

}  // namespace
}  // namespace pelage::animation
