// Fur presets: the paper's Figure 2 values, validation of every field, round trips.
#include <gtest/gtest.h>

#include <string>

#include "pelage/fur/preset.h"
#include "pelage/util/error.h"
#include "pelage/util/log.h"
#include "support/files.h"

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
  p.coverage = 0.0;  // the default counts by coverage; this one by density
  p.densityPerM2 = 250000;
  p.lengthRegion.shape = RegionShape::Box;
  p.lengthRegion.boxMin = Eigen::Vector3f(-1, -2, -3);
  p.lengthRegion.boxMax = Eigen::Vector3f(1, 2, 3);
  p.lengthRegion.scale = 0.5f;
  p.coats[kUndercoat].style = HairStyle::Tube;
  p.coats[kUndercoat].curlRadius = 0.25f;
  p.coats[kUndercoat].curlTurns = 4.0f;
  p.coats[kOvercoat].frizz = {.amplitudeMm = 2.5f, .frequency = 7.0f, .tipWeight = 3.0f};
  p.coats[kOvercoat].clump = {.density = 0.5f, .strength = 0.7f, .shape = 2.0f, .radiusMm = 8.0f};
  p.up = Eigen::Vector3f(0, 1, 0);
  const FurParams q = parseFurPreset(furPresetJson(p), "round trip");
  EXPECT_EQ(furPresetJson(q), furPresetJson(p));
  EXPECT_DOUBLE_EQ(q.densityPerM2, 250000);
  EXPECT_EQ(q.coats[kUndercoat].style, HairStyle::Tube);
  EXPECT_FLOAT_EQ(q.coats[kUndercoat].curlTurns, 4.0f);
  EXPECT_FLOAT_EQ(q.coats[kOvercoat].frizz.amplitudeMm, 2.5f);
  EXPECT_FLOAT_EQ(q.coats[kOvercoat].frizz.frequency, 7.0f);
  EXPECT_FLOAT_EQ(q.coats[kOvercoat].frizz.tipWeight, 3.0f);
  EXPECT_FLOAT_EQ(q.coats[kOvercoat].clump.density, 0.5f);
  EXPECT_FLOAT_EQ(q.coats[kOvercoat].clump.radiusMm, 8.0f);
  test::TempDir dir;
  saveFurPreset(dir.file("mine.json"), p);
  EXPECT_EQ(furPresetJson(loadFurPreset(dir.file("mine.json"))), furPresetJson(p));
}

// Every field of `p` but its name, as the preset file text writes them.
std::string fieldsOf(FurParams p) {
  p.name = "";
  return furPresetJson(p);
}

TEST(PresetInheritance, APartialPresetStartsFromTheDefault) {
  // {"lengthScale": 1.0} is the default preset: every field, so every hair, the same.
  const FurParams d = loadFurPreset("default");
  const FurParams p = parseFurPreset(R"({"lengthScale": 1.0})", "partial.json");
  EXPECT_EQ(p.name, "partial");
  EXPECT_EQ(fieldsOf(p), fieldsOf(d));
  const FurParams longer = parseFurPreset(R"({"lengthScale": 1.5})", "longer.json");
  EXPECT_FLOAT_EQ(longer.lengthScale, 1.5f);
  EXPECT_FLOAT_EQ(longer.undercoatShare, d.undercoatShare);
  EXPECT_EQ(longer.coats[kOvercoat].color.source, ColorSource::Creature);
  // A coat states what differs from the base's coat: the undercoat keeps the default's.
  const FurParams stiff = parseFurPreset(R"({"overcoat": {"stiffness": 0.9}})", "stiff.json");
  EXPECT_FLOAT_EQ(stiff.coats[kOvercoat].stiffness, 0.9f);
  EXPECT_FLOAT_EQ(stiff.coats[kUndercoat].stiffness, d.coats[kUndercoat].stiffness);
  EXPECT_FLOAT_EQ(stiff.coats[kUndercoat].lengthFactor, d.coats[kUndercoat].lengthFactor);
}

TEST(PresetInheritance, BaseNamesABuiltinOrAFileAndChains) {
  test::TempDir dir;
  test::writeText(dir.file("b.json"), R"({"base": "fig9", "hairs": 1234, "seed": 5})");
  test::writeText(dir.file("a.json"), R"({"base": "b.json", "seed": 7})");
  const FurParams fig9 = loadFurPreset("fig9");
  const FurParams a = loadFurPreset(dir.file("a.json"));
  EXPECT_EQ(a.name, "a");
  EXPECT_DOUBLE_EQ(a.hairs, 1234);
  EXPECT_EQ(a.seed, 7u);
  FurParams expected = fig9;
  expected.hairs = 1234;
  expected.seed = 7;
  EXPECT_EQ(fieldsOf(a), fieldsOf(expected));
  // "hairs" over a base with a density replaces it, and the other way round.
  test::writeText(dir.file("dense.json"), R"({"density": 50000})");
  test::writeText(dir.file("counted.json"), R"({"base": "dense.json", "hairs": 10})");
  EXPECT_DOUBLE_EQ(loadFurPreset(dir.file("dense.json")).densityPerM2, 50000);
  EXPECT_DOUBLE_EQ(loadFurPreset(dir.file("counted.json")).densityPerM2, 0.0);
  EXPECT_DOUBLE_EQ(loadFurPreset(dir.file("counted.json")).hairs, 10);
}

TEST(PresetInheritance, LoopsAndUnknownBasesAreErrors) {
  test::TempDir dir;
  test::writeText(dir.file("a.json"), R"({"base": "b.json"})");
  test::writeText(dir.file("b.json"), R"({"base": "a.json"})");
  test::expectInputError([&] { loadFurPreset(dir.file("a.json")); }, {"its own base", "a.json"});
  test::writeText(dir.file("c.json"), R"({"base": "fig99"})");
  test::expectInputError([&] { loadFurPreset(dir.file("c.json")); },
                         {"c.json", "'base'", "unknown fur preset 'fig99'", "fig8"});
  test::writeText(dir.file("d.json"), R"({"base": "missing.json"})");
  test::expectInputError([&] { loadFurPreset(dir.file("d.json")); }, {"missing.json"});
}

TEST(PresetInheritance, FieldsApplyOverAnyParameters) {
  const FurParams fig8 = loadFurPreset("fig8");
  const FurParams p =
      applyFurPresetFields(fig8, R"({"overcoat": {"stiffness": 0.6}})", "--fur-set options");
  EXPECT_EQ(p.name, "fig8");
  FurParams expected = fig8;
  expected.coats[kOvercoat].stiffness = 0.6f;
  EXPECT_EQ(furPresetJson(p), furPresetJson(expected));
  test::expectInputError(
      [&] { applyFurPresetFields(fig8, R"({"overcoat": {"stiffness": 2}})", "--fur-set options"); },
      {"--fur-set options", "overcoat.stiffness", "[0, 1]"});
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
        BadPreset{"HairsAndDensity", R"({"hairs": 10, "density": 5})", "not several"},
        BadPreset{"WrongType", R"({"undercoatShare": "half"})", "expected a number"},
        BadPreset{"BadStyle", R"({"overcoat": {"style": "dreadlocks"}})",
                  "accepted: line, polyline, curve, tube"},
        BadPreset{"ColorRange", R"({"overcoat": {"diffuse": [0.3, 1.4, 0]}})",
                  "out of range [0, 1]"},
        BadPreset{"ColorShape", R"({"overcoat": {"specular": [0.3, 0.2]}})", "3 numbers"},
        BadPreset{"CurvePoints", R"({"undercoat": {"curvePoints": 100}})", "[2, 64]"},
        BadPreset{"FrizzAmplitude", R"({"overcoat": {"frizz": {"amplitude": 150}}})",
                  "overcoat.frizz.amplitude': value 150 is out of range [0, 100]"},
        BadPreset{"ClumpDensity", R"({"undercoat": {"clump": {"density": -1}}})",
                  "undercoat.clump.density': value -1 is out of range [0, 100]"},
        BadPreset{"FrizzField", R"({"overcoat": {"frizz": {"amplitude": 1, "freq": 2}}})",
                  "unknown field 'overcoat.frizz.freq'"},
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
