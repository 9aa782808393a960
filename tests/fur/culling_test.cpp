// Distance culling (Van Gelder & Wilhelms 1997, sec. 3.3): 1/c of the hairs on average, a prefix
// of each triangle's creation order, stable from frame to frame.
#include <gtest/gtest.h>

#include <cmath>

#include "pelage/fur/culling.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

TEST(Culling, FactorIsDistanceOverReferenceAtLeastOne) {
  FurView v;
  v.culling = true;
  v.referenceDistance = 0.5f;
  v.viewDistance = 2.0f;
  EXPECT_FLOAT_EQ(cullingFactor(v), 4.0f);
  v.viewDistance = 0.2f;
  EXPECT_FLOAT_EQ(cullingFactor(v), 1.0f);  // closer than the reference: every hair
  v.viewDistance = 2.0f;
  v.culling = false;
  EXPECT_FLOAT_EQ(cullingFactor(v), 1.0f);
}

// c = s_ref / s with s = H / (2 d tan(fovY / 2)) pixels per metre: exact on round numbers.
TEST(Culling, FactorIsTheReferenceScaleOverTheCamerasScale) {
  EXPECT_FLOAT_EQ(pixelsPerMeter(2.0f, 90.0f, 540), 135.0f);  // tan 45 = 1
  FurView v;
  v.culling = true;
  v.referenceDistance = 0.5f;
  v.viewDistance = 2.0f;
  v.referenceFovYDegrees = 45.0f;
  v.fovYDegrees = 90.0f;
  v.referenceHeight = 1080;
  v.imageHeight = 540;
  // Distance x4, a field of view seeing 1 / tan(22.5) times more, half the pixels.
  const double tan225 = std::tan(22.5 * 3.14159265358979323846 / 180.0);
  EXPECT_NEAR(cullingFactor(v), 4.0 / tan225 * 2.0, 1e-4);
  // A camera that sees the creature as large as the reference does: c = 1.
  v.imageHeight = 2160;
  v.fovYDegrees = 45.0f;
  v.viewDistance = 1.0f;
  EXPECT_FLOAT_EQ(cullingFactor(v), 1.0f);
  v.imageHeight = 1080;
  EXPECT_FLOAT_EQ(cullingFactor(v), 2.0f);
}

TEST(Culling, KeepsOneOverCOnAverageAsAPrefixOfCreationOrder) {
  const skin::SkinMesh s = test::makeGrid(50, 0.01f, 0.01f);  // 5000 triangles
  const FurRoots r = growRoots(s, test::simpleParams(HairStyle::Line, 37000));
  const CoatRoots& cr = r.coats[0];
  for (float c : {1.0f, 1.5f, 2.0f, 5.0f, 40.0f}) {
    std::vector<std::int32_t> drawnStart;
    const std::int64_t drawn = computeDrawnStart(cr, coatSeed(r.seed, 0), c, drawnStart);
    // Expected sum of k / c; each triangle's rounding adds variance <= 1/4.
    const double expected = static_cast<double>(cr.size()) / c;
    EXPECT_NEAR(static_cast<double>(drawn), expected, 5 * std::sqrt(s.numTriangles() * 0.25))
        << "c " << c;
    EXPECT_EQ(drawnStart.back(), drawn);
    for (std::int32_t t = 0; t < s.numTriangles(); ++t) {
      const std::int32_t k = cr.triangleStart[static_cast<std::size_t>(t) + 1] -
                             cr.triangleStart[static_cast<std::size_t>(t)];
      const std::int32_t kd =
          drawnStart[static_cast<std::size_t>(t) + 1] - drawnStart[static_cast<std::size_t>(t)];
      ASSERT_GE(kd, 0);
      ASSERT_LE(kd, k);
      // floor(k / c + u) is floor(k / c) or one more.
      ASSERT_GE(kd, static_cast<std::int32_t>(std::floor(static_cast<float>(k) / c)));
      ASSERT_LE(kd, static_cast<std::int32_t>(std::floor(static_cast<float>(k) / c)) + 1);
    }
    if (c == 1.0f) {
      EXPECT_EQ(drawnStart, cr.triangleStart);
    }
  }
}

TEST(Culling, SmallTrianglesAreNotAllRoundedAway) {
  // 0.74 hairs per triangle at c = 2: random rounding keeps 0.37 per triangle on average.
  const skin::SkinMesh s = test::makeGrid(50, 0.01f, 0.01f);
  const FurRoots r = growRoots(s, test::simpleParams(HairStyle::Line, 3700));
  std::vector<std::int32_t> drawnStart;
  const std::int64_t drawn = computeDrawnStart(r.coats[0], coatSeed(r.seed, 0), 2.0f, drawnStart);
  EXPECT_NEAR(static_cast<double>(drawn), static_cast<double>(r.coats[0].size()) / 2,
              5 * std::sqrt(5000 * 0.25));
}

TEST(Culling, FramesDrawTheFirstHairsOfEachTriangleAndDoNotFlicker) {
  const skin::SkinMesh s = test::makeGrid(20, 0.01f, 0.01f);
  const FurParams p = test::simpleParams(HairStyle::Polyline, 8000);
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  FurView view;
  view.culling = true;
  view.referenceDistance = 1.0f;
  view.viewDistance = 3.0f;
  const FurFrame a = test::furFrame(s, r, p, d, view);
  const FurFrame b = test::furFrame(s, r, p, d, view);
  EXPECT_TRUE(test::sameHairs(a, b));
  EXPECT_FLOAT_EQ(a.cullingFactor, 3.0f);
  const HairBuffers& hb = a.coats[0];
  // Every drawn hair id is among the first k' roots of its triangle, each once, in order.
  std::vector<std::int32_t> drawnStart;
  computeDrawnStart(r.coats[0], coatSeed(r.seed, 0), 3.0f, drawnStart);
  ASSERT_EQ(hb.drawn, drawnStart.back());
  std::int64_t i = 0;
  for (std::int32_t t = 0; t < s.numTriangles(); ++t)
    for (std::int32_t k = 0;
         k < drawnStart[static_cast<std::size_t>(t) + 1] - drawnStart[static_cast<std::size_t>(t)];
         ++k)
      ASSERT_EQ(hb.hairIds[static_cast<std::size_t>(i++)],
                r.coats[0].triangleStart[static_cast<std::size_t>(t)] + k);
  // The drawn hairs are exactly the same hairs (bit for bit) as in the unculled frame.
  const FurFrame all = test::furFrame(s, r, p, d);
  const HairBuffers& full = all.coats[0];
  for (std::int64_t h = 0; h < hb.drawn; ++h)
    for (int k = 0; k < 8; ++k)
      ASSERT_EQ(test::point(hb, h, k),
                test::point(full, hb.hairIds[static_cast<std::size_t>(h)], k));
  // Nearer than the reference: all hairs.
  view.viewDistance = 0.5f;
  EXPECT_EQ(test::furFrame(s, r, p, d, view).coats[0].drawn, r.coats[0].size());
}

TEST(Culling, TheDefaultReferenceIsWhereARootIsHalfAPixelWide) {
  // 1 mm at 90 degrees in a 1000-pixel image: s = 1000 / (2 d) pixels per metre, so the root is
  // k = kReferenceRootPixels wide at d = 1 / (2 k) m; twice the width, twice the distance; the
  // reference image's height scales it too.
  FurParams p;
  p.coats[kOvercoat].width = {1.0f, 0.1f};
  p.culling.fovYDegrees = 90.0f;
  p.culling.referenceHeight = 1000;
  const float d = 0.5f / kReferenceRootPixels;
  EXPECT_NEAR(defaultReferenceDistance(p), d, 1e-6f);
  p.coats[kOvercoat].width.rootMm = 2.0f;
  EXPECT_NEAR(defaultReferenceDistance(p), 2.0f * d, 1e-6f);
  p.culling.referenceHeight = 500;
  EXPECT_NEAR(referenceDistance(p), d, 1e-6f);
  p.culling.referenceDistance = 3.0f;
  EXPECT_EQ(referenceDistance(p), 3.0f);
}

}  // namespace
}  // namespace pelage::fur
