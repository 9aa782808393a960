// Fur presets: the paper's Figure 2 values, validation of every field, round trips.
#include <gtest/gtest.h>

#include <string>

#include "pelage/fur/preset.h"
#include "pelage/util/error.h"
#include "pelage/util/log.h"
#include "test_support.h"

namespace pelage::fur {
namespace {

void expectColor(const Eigen::Vector3f& c, float r, float g, float b) {
  EXPECT_FLOAT_EQ(c.x(), r);
  EXPECT_FLOAT_EQ(c.y(), g);
  EXPECT_FLOAT_EQ(c.z(), b);
}

TEST(Preset, BuiltinsAreListed) {
  const std::vector<std::string> names = builtinPresetNames();
  for (const char* n : {"default", "fig8", "fig9"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
}

TEST(Preset, Fig8HasTheFigure2Values) {
  const FurParams p = loadFurPreset("fig8");
  EXPECT_EQ(p.name, "fig8");
  EXPECT_DOUBLE_EQ(p.hairs, 90000);
  EXPECT_FLOAT_EQ(p.undercoatShare, 0.0f);
  const CoatParams& c = p.coats[kOvercoat];
  EXPECT_EQ(c.style, HairStyle::Polyline);
  EXPECT_FLOAT_EQ(c.stiffness, 0.2f);
  EXPECT_FLOAT_EQ(c.normalRandomize, 0.0f);
  EXPECT_FLOAT_EQ(c.hairEndRandomize, 0.2f);
  EXPECT_FLOAT_EQ(c.segmentDirectionWeight, 0.2f);
  expectColor(c.material.ambient, 0.3f, 0.14f, 0.0f);
  expectColor(c.material.diffuse, 0.3f, 0.14f, 0.0f);
  expectColor(c.material.specular, 0.6f, 0.6f, 0.6f);
  EXPECT_FLOAT_EQ(c.material.shininess, 16.0f);
}

TEST(Preset, Fig9HasTheFigure2ValuesAndAnUndercoat) {
  const FurParams p = loadFurPreset("fig9");
  EXPECT_DOUBLE_EQ(p.hairs, 500000);
  EXPECT_GT(p.undercoatShare, 0.0f);
  for (int k = 0; k < kCoatCount; ++k) {
    const CoatParams& c = p.coats[static_cast<std::size_t>(k)];
    EXPECT_EQ(c.style, HairStyle::Polyline);
    EXPECT_FLOAT_EQ(c.normalRandomize, 0.5f);
    EXPECT_FLOAT_EQ(c.hairEndRandomize, 0.1f);
    EXPECT_FLOAT_EQ(c.segmentDirectionWeight, 0.3f);
    expectColor(c.material.ambient, 0.15f, 0.07f, 0.0f);
    expectColor(c.material.diffuse, 0.3f, 0.14f, 0.0f);
    expectColor(c.material.specular, 0.6f, 0.6f, 0.6f);
    EXPECT_FLOAT_EQ(c.material.shininess, 50.0f);
  }
  EXPECT_FLOAT_EQ(p.coats[kOvercoat].stiffness, 0.2f);
  EXPECT_FLOAT_EQ(p.coats[kOvercoat].lengthFactor, 1.0f);
  EXPECT_FLOAT_EQ(p.coats[kUndercoat].lengthFactor, 0.3f);
  EXPECT_GT(p.coats[kUndercoat].stiffness, p.coats[kOvercoat].stiffness)
      << "sec. 3.1: undercoat more stiff";
}

TEST(Preset, RoundTripsThroughJson) {
  FurParams p = loadFurPreset("default");
  p.densityPerM2 = 250000;
  p.lengthRegion.shape = RegionShape::Box;
  p.lengthRegion.boxMin = Eigen::Vector3f(-1, -2, -3);
  p.lengthRegion.boxMax = Eigen::Vector3f(1, 2, 3);
  p.lengthRegion.scale = 0.5f;
  p.coats[kUndercoat].style = HairStyle::Tube;
  p.coats[kUndercoat].curlRadius = 0.25f;
  p.coats[kUndercoat].curlTurns = 4.0f;
  p.up = Eigen::Vector3f(0, 1, 0);
  const FurParams q = parseFurPreset(furPresetJson(p), "round trip");
  EXPECT_EQ(furPresetJson(q), furPresetJson(p));
  EXPECT_DOUBLE_EQ(q.densityPerM2, 250000);
  EXPECT_EQ(q.coats[kUndercoat].style, HairStyle::Tube);
  EXPECT_FLOAT_EQ(q.coats[kUndercoat].curlTurns, 4.0f);
  test::TempDir dir;
  saveFurPreset(dir.file("mine.json"), p);
  EXPECT_EQ(furPresetJson(loadFurPreset(dir.file("mine.json"))), furPresetJson(p));
}

struct BadPreset {
  const char* name;
  const char* json;
  const char* expect;  // part of the message
};

// gtest names the case by this (not its bytes) in test names and failures.
void PrintTo(const BadPreset& c, std::ostream* os) {
  *os << c.name;
}

class PresetRejects : public ::testing::TestWithParam<BadPreset> {};

TEST_P(PresetRejects, WithAClearMessage) {
  try {
    parseFurPreset(GetParam().json, "bad.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bad.json"), std::string::npos) << m;
    EXPECT_NE(m.find(GetParam().expect), std::string::npos) << m;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Presets, PresetRejects,
    ::testing::Values(
        BadPreset{"UnknownField", R"({"hairs": 10, "stifness": 0.2})", "unknown field 'stifness'"},
        BadPreset{"UnknownCoatField", R"({"overcoat": {"colour": [1, 0, 0]}})",
                  "unknown field 'overcoat.colour'"},
        BadPreset{"StiffnessRange", R"({"overcoat": {"stiffness": 1.5}})",
                  "overcoat.stiffness': value 1.5 is out of range [0, 1]"},
        BadPreset{"NegativeHairs", R"({"hairs": -5})", "out of range [0, 2e+07]"},
        BadPreset{"TooManyHairs", R"({"hairs": 3e9})", "'hairs'"},
        BadPreset{"HairsAndDensity", R"({"hairs": 10, "density": 5})", "not both"},
        BadPreset{"WrongType", R"({"undercoatShare": "half"})", "expected a number"},
        BadPreset{"BadStyle", R"({"overcoat": {"style": "dreadlocks"}})",
                  "accepted: line, polyline, curve, tube"},
        BadPreset{"ColorRange", R"({"overcoat": {"diffuse": [0.3, 1.4, 0]}})",
                  "out of range [0, 1]"},
        BadPreset{"ColorShape", R"({"overcoat": {"specular": [0.3, 0.2]}})", "3 numbers"},
        BadPreset{"CurvePoints", R"({"undercoat": {"curvePoints": 100}})", "[2, 64]"},
        BadPreset{"ZeroUp", R"({"up": [0, 0, 0]})", "no direction"},
        BadPreset{
            "RegionBoth",
            R"({"lengthRegion": {"sphere": {"center": [0,0,0], "radius": 1}, "box": {"min": [0,0,0], "max": [1,1,1]}}})",
            "exactly one"},
        BadPreset{"BoxInsideOut", R"({"lengthRegion": {"box": {"min": [0,0,2], "max": [1,1,1]}}})",
                  "min <= max"},
        BadPreset{"Malformed", R"({"hairs": 10,)", "malformed JSON"},
        BadPreset{"NotAnObject", R"([1, 2])", "expected a JSON object"}),
    [](const auto& bad) { return std::string(bad.param.name); });

TEST(Preset, UnknownNamesAndMissingFilesAreErrors) {
  try {
    loadFurPreset("fig10");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("built-in: default, fig8, fig9"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(loadFurPreset("/nonexistent/fur.json"), InputError);
}

TEST(FurParams, ClampedStiffnessWarnsAndFloppinessHasAFloor) {
  EXPECT_FLOAT_EQ(floppiness(0.2f), 0.8f);
  EXPECT_FLOAT_EQ(floppiness(1.0f), 0.02f);
  EXPECT_FLOAT_EQ(floppiness(0.0f), 1.0f);
  std::vector<std::string> warnings;
  const WarningSink old = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
  const FurParams p = parseFurPreset(
      R"({"overcoat": {"stiffness": 1.0}, "undercoat": {"stiffness": 0.5}})", "stiff.json");
  setWarningSink(old);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("overcoat.stiffness"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("0.02"), std::string::npos) << warnings[0];
  EXPECT_FLOAT_EQ(p.coats[kOvercoat].stiffness, 1.0f)
      << "the user's value is kept; floppiness is clamped";
}

TEST(FurParams, ValidationNamesTheFieldAndRange) {
  FurParams p;
  p.coats[kUndercoat].tubeSides = 2;
  try {
    validateFurParams(p, "viewer");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("viewer: undercoat.tubeSides = 2 is out of range [3, 32]"),
              std::string::npos)
        << e.what();
  }
  FurParams q;
  q.up = Eigen::Vector3f(0, 0, -3);
  validateFurParams(q, "x");
  EXPECT_TRUE(q.up.isApprox(Eigen::Vector3f(0, 0, -1)));
  EXPECT_EQ(parseStyle("tube", "x"), HairStyle::Tube);
  EXPECT_STREQ(styleName(HairStyle::Curve), "curve");
}

}  // namespace
}  // namespace pelage::fur
