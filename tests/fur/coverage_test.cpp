// How much skin a coat hides (fur/coverage.h): exact densities and optical depths on a small grid,
// the coverage field's hair count, and the roots it grows.
#include <gtest/gtest.h>

#include <cmath>

#include "pelage/fur/coverage.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "support/files.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

// 2 x 2 cells of 0.5 m: 1 m^2 of skin, every vertex's fur 20 mm long.
FurParams gridParams() {
  FurParams p;
  p.setHairCount(10000);
  p.undercoatShare = 0.25f;
  p.coats[kUndercoat].lengthFactor = 0.5f;
  for (CoatParams& c : p.coats) c.width = StrandWidth{0.3f, 0.1f};
  return p;
}

TEST(Coverage, ExactOnAGrid) {
  const skin::SkinMesh s = test::makeGrid(2, 0.5f, 0.02f);
  const FurCoverage f = estimateCoverage(s, gridParams());
  EXPECT_NEAR(f.furredAreaM2, 1.0, 1e-9);
  const CoatCoverage& over = f.coats[kOvercoat];
  const CoatCoverage& under = f.coats[kUndercoat];
  EXPECT_DOUBLE_EQ(over.hairs, 7500);
  EXPECT_NEAR(over.densityPerCm2, 0.75, 1e-12);
  EXPECT_NEAR(over.meanLengthMm, 20.0, 1e-4);
  EXPECT_NEAR(over.meanWidthMm, 0.2, 1e-7);
  EXPECT_NEAR(over.opticalDepth, 7500 * 0.02 * 0.0002, 1e-8);  // n L w
  EXPECT_DOUBLE_EQ(under.hairs, 2500);
  EXPECT_NEAR(under.meanLengthMm, 10.0, 1e-4);
  EXPECT_NEAR(under.opticalDepth, 2500 * 0.01 * 0.0002, 1e-8);
  EXPECT_NEAR(f.opticalDepth, 0.035, 1e-8);
  EXPECT_NEAR(f.hiddenShare, 1.0 - std::exp(-kProjectedShare * 0.035), 1e-9);
  // Twice the lengths or twice the widths: twice the optical depth.
  FurParams longer = gridParams();
  longer.lengthScale = 2.0f;
  EXPECT_NEAR(estimateCoverage(s, longer).opticalDepth, 0.07, 1e-8);
  FurParams wider = gridParams();
  for (CoatParams& c : wider.coats) c.width = StrandWidth{0.6f, 0.2f};
  EXPECT_NEAR(estimateCoverage(s, wider).opticalDepth, 0.07, 1e-8);
}

TEST(Coverage, TheAreaWeightsTheLengths) {
  // A unit square whose corner vertex 3 grows 40 mm fur, the others 10 mm: both triangles hold
  // vertex 3, so each has a vertex mean of 20 mm, and so has the skin.
  skin::SkinMesh s =
      test::makeSkin({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 3}, {0, 3, 2}}, 0.01f);
  float* len = s.mesh.property(s.furLength).data_vector().data();
  len[3] = 0.04f;  // triangle means (10 + 10 + 40) / 3 = 20 mm each
  FurParams p = gridParams();
  p.undercoatShare = 0.0f;
  EXPECT_NEAR(estimateCoverage(s, p).coats[kOvercoat].meanLengthMm, 20.0, 1e-4);
}

TEST(Coverage, ACoverageAsksForTheHairsThatHideThatShare) {
  const skin::SkinMesh s = test::makeGrid(8, 0.125f, 0.02f);
  for (const double share : {0.5, 0.9, 0.99}) {
    FurParams p = gridParams();
    p.coverage = share;
    const double n = hairsForCoverage(s, p, share);
    // tau = -ln(1 - share) / k over 1 m^2, each hair 0.75 x 20 mm x 0.2 mm + 0.25 x 10 x 0.2.
    const double perHair = 0.75 * 0.02 * 0.0002 + 0.25 * 0.01 * 0.0002;
    EXPECT_DOUBLE_EQ(n, std::ceil(-std::log(1.0 - share) / kProjectedShare / perHair)) << share;
    const FurCoverage f = estimateCoverage(s, p);
    EXPECT_NEAR(f.hiddenShare, share, 1e-4) << share;
    EXPECT_DOUBLE_EQ(f.coats[kOvercoat].hairs + f.coats[kUndercoat].hairs, n);
    // The roots it grows: each of the 128 triangles rounds its share by less than one hair.
    const FurRoots roots = growRoots(s, p);
    EXPECT_NEAR(static_cast<double>(roots.total()), n, 2.0 * 128) << share;
  }
  // A skin without fur needs none.
  EXPECT_EQ(hairsForCoverage(test::makeGrid(2, 0.5f, 0.0f), gridParams(), 0.9), 0.0);
}

TEST(Coverage, PresetsSetItAndItReplacesTheOtherCounts) {
  const FurParams p = parseFurPreset(R"({"coverage": 0.95})", "covered.json");
  EXPECT_DOUBLE_EQ(p.coverage, 0.95);
  EXPECT_DOUBLE_EQ(p.densityPerM2, 0.0);
  EXPECT_EQ(parseFurPreset(furPresetJson(p), "again").coverage, 0.95);
  const FurParams counted = applyFurPresetFields(p, R"({"hairs": 500})", "--fur-set options");
  EXPECT_EQ(counted.coverage, 0.0);
  EXPECT_EQ(counted.hairs, 500);
  const FurParams dense = applyFurPresetFields(p, R"({"density": 500})", "--fur-set options");
  EXPECT_EQ(dense.coverage, 0.0);
  test::expectInputError([] { parseFurPreset(R"({"coverage": 1.0})", "c.json"); },
                         {"c.json", "coverage", "[0, 0.999]"});
  test::expectInputError([] { parseFurPreset(R"({"coverage": 0.9, "hairs": 4})", "c.json"); },
                         {"c.json", "give one of 'hairs'"});
}

}  // namespace
}  // namespace pelage::fur
