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

// A unit square of two triangles, (0, 1, 3) and (0, 3, 2), every vertex's fur 10 mm but vertex
// 2's, 40 mm: triangle means 10 and 20 mm, an area-weighted mean of 15 mm.
skin::SkinMesh twoTriangles() {
  skin::SkinMesh s =
      test::makeSkin({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 1, 3}, {0, 3, 2}}, 0.01f);
  s.mesh.property(s.furLength).data_vector()[2] = 0.04f;
  return s;
}

TEST(Coverage, ADensityGroomCountsWhereTheHairsGo) {
  const skin::SkinMesh s = twoTriangles();
  FurParams p = gridParams();
  p.undercoatShare = 0.0f;
  EXPECT_NEAR(estimateCoverage(s, p).coats[kOvercoat].meanLengthMm, 15.0, 1e-4);
  // Vertex 2 of density 4: the second triangle's mean density is 2, so it gets two thirds of the
  // hairs: a mean length of (1 x 10 + 2 x 20) / 3 mm over the hairs.
  VertexGroom groom;
  groom.density = {1.0f, 1.0f, 4.0f, 1.0f};
  const FurCoverage f = estimateCoverage(s, p, nullptr, &groom);
  EXPECT_NEAR(f.coats[kOvercoat].meanLengthMm, 50.0 / 3.0, 1e-4);
  EXPECT_NEAR(f.coats[kOvercoat].opticalDepth, 10000 * (0.05 / 3.0) * 0.0002, 1e-8);
  EXPECT_DOUBLE_EQ(f.coats[kOvercoat].hairs, 10000);  // the count stays params'
  // The same density everywhere moves no hair: the figures without a groom.
  groom.density.assign(4, 3.0f);
  EXPECT_NEAR(estimateCoverage(s, p, nullptr, &groom).opticalDepth,
              estimateCoverage(s, p).opticalDepth, 1e-12);
}

TEST(Coverage, AWidthGroomWidensEachCoatItScales) {
  const skin::SkinMesh s = twoTriangles();
  const FurParams p = gridParams();
  const FurCoverage plain = estimateCoverage(s, p);
  // The overcoat twice as wide everywhere, the undercoat as it was: the overcoat's mean width and
  // optical depth double, the undercoat's stay.
  VertexGroom groom;
  groom.widthScale.assign(4, Eigen::Vector2f(2.0f, 1.0f));
  const FurCoverage wide = estimateCoverage(s, p, nullptr, &groom);
  EXPECT_NEAR(wide.coats[kOvercoat].meanWidthMm, 2.0 * plain.coats[kOvercoat].meanWidthMm, 1e-9);
  EXPECT_NEAR(wide.coats[kOvercoat].opticalDepth, 2.0 * plain.coats[kOvercoat].opticalDepth, 1e-9);
  EXPECT_NEAR(wide.coats[kUndercoat].opticalDepth, plain.coats[kUndercoat].opticalDepth, 1e-12);
  EXPECT_GT(wide.hiddenShare, plain.hiddenShare);
  // A scale that rises where the hairs are long: the optical depth takes the mean of the product.
  // On triangle (0, 3, 2), lengths (10, 10, 40) mm and scales (1, 1, 3): E[L s] = (10 + 10 + 120 +
  // 60 x 5) / 12 = 110 / 3 mm, not E[L] E[s] = 20 x 5 / 3; on (0, 1, 3), 10 mm at scale 1.
  groom.widthScale.assign(4, Eigen::Vector2f(1.0f, 1.0f));
  groom.widthScale[2] = Eigen::Vector2f(3.0f, 3.0f);
  FurParams over = p;
  over.undercoatShare = 0.0f;
  const FurCoverage f = estimateCoverage(s, over, nullptr, &groom);
  EXPECT_NEAR(f.coats[kOvercoat].opticalDepth, 10000 * 0.5 * (0.01 + 0.11 / 3.0) * 0.0002, 1e-8);
  EXPECT_NEAR(f.coats[kOvercoat].meanWidthMm, 0.2 * 0.5 * (1.0 + 5.0 / 3.0), 1e-7);
}

TEST(Coverage, TheGroomedEstimateIsTheMeanOverTheRootsGrown) {
  // Statistical: the roots growRoots grows with a density and a width groom, their lengths and
  // scales interpolated at each root, give the estimate's n E[L w] within sampling error.
  const skin::SkinMesh s = twoTriangles();
  FurParams p = gridParams();
  p.undercoatShare = 0.0f;
  p.setHairCount(40000);
  Groom groom;
  groom.vertex.density = {1.0f, 0.5f, 4.0f, 1.0f};
  groom.vertex.widthScale = {{1.0f, 1.0f}, {0.5f, 1.0f}, {3.0f, 1.0f}, {1.0f, 1.0f}};
  const FurRoots roots = growRoots(s, p, groom);
  const CoatRoots& cr = roots.coats[kOvercoat];
  ASSERT_EQ(cr.widthScale.size(), static_cast<std::size_t>(cr.size()));
  const float* len = s.furLengths();
  double sumLs = 0.0, sumLs2 = 0.0;
  for (std::int64_t k = 0; k < cr.size(); ++k) {
    const std::size_t ks = static_cast<std::size_t>(k);
    const std::int32_t* v = s.triangles.data() + 3 * cr.triangle[ks];
    const float* b = roots.barycentric.data() + 4 * cr.tableIndex[ks];
    const double ls = (b[0] * len[v[0]] + b[1] * len[v[1]] + b[2] * len[v[2]]) * cr.widthScale[ks];
    sumLs += ls;
    sumLs2 += ls * ls;
  }
  const double n = static_cast<double>(cr.size());
  const double mean = sumLs / n;
  const double sd = std::sqrt(std::max(sumLs2 / n - mean * mean, 0.0));
  const double grown = n * mean * 0.0002;  // over 1 m^2, mean width 0.2 mm
  const double expected = estimateCoverage(s, p, nullptr, &groom.vertex).opticalDepth;
  // Five standard errors (the 2048-entry barycentric table adds its own small spread).
  EXPECT_NEAR(grown, expected, 5.0 * std::sqrt(n) * sd * 0.0002) << grown << " vs " << expected;
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
