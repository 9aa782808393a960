// The fur on the default monkey (~130k triangles): building its skin takes seconds (minutes under
// the sanitizers), so these run in their own binary labelled slow. Small-skin versions of the same
// checks are in generate_test.cpp and roots_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "pelage/fur/culling.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/roots.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

TEST(FurOnMonkey, EveryStyleMatchesTheReferenceAndIsDeterministic) {
  const test::MonkeySkin& m = test::monkeySkin();
  test::checkStylesAgainstReference(m.skin, m.rest, 12000, Eigen::Vector3f(0.38f, 0.0f, 0.43f));
}

TEST(FurOnMonkey, LengthsAreTheInterpolatedVertexLengthsAndTheFaceSetsTheReferenceDistance) {
  // sec. 3.2: L = b1 len1 + b2 len2 + b3 len3 (times the scales). Line hairs end at distance L.
  const test::MonkeySkin& m = test::monkeySkin();
  FurParams p = test::simpleParams(HairStyle::Line, 20000);
  p.lengthScale = 1.5f;
  const FurRoots r = growRoots(m.skin, p);
  const FurFrame f = test::furFrame(m.skin, r, p, m.rest);
  const HairBuffers& hb = f.coats[0];
  const float* len = m.skin.furLengths();
  double shortest = 1.0, longest = 0.0;
  for (std::int64_t h = 0; h < hb.drawn; ++h) {
    const CoatRoots& cr = r.coats[0];
    const auto root = static_cast<std::size_t>(hb.hairIds[static_cast<std::size_t>(h)]);
    const std::int32_t* tv = m.skin.triangles.data() + 3 * cr.triangle[root];
    const float* b = r.barycentric.data() + 4 * cr.tableIndex[root];
    const double L = 1.5 * (b[0] * len[tv[0]] + b[1] * len[tv[1]] + b[2] * len[tv[2]]);
    // Float coordinates of ~0.5 m carry 3e-8 rounding each.
    ASSERT_NEAR((test::point(hb, h, 1) - test::point(hb, h, 0)).norm(), L, 1e-6 * L + 1e-7) << h;
    shortest = std::min(shortest, L);
    longest = std::max(longest, L);
  }
  EXPECT_NEAR(longest, 1.5 * 0.018, 1e-6) << "the monkey's body fur";
  EXPECT_LT(shortest, 0.2 * longest) << "shorter on the face, hands and feet";

  // sec. 3.3: every hair is drawn while a root is at least kReferenceRootPixels wide in the
  // reference image (0.4 mm, 1080 pixels, 45 degrees: 2.09 m at a quarter pixel).
  const FurParams defaults;
  const float d = defaultReferenceDistance(defaults);
  EXPECT_NEAR(
      d,
      0.4e-3f * 1080.0f /
          (2.0f * std::tan(22.5f * static_cast<float>(M_PI) / 180.0f) * kReferenceRootPixels),
      1e-5f);
  FurParams given;
  given.culling.referenceDistance = 0.7f;
  EXPECT_FLOAT_EQ(referenceDistance(given), 0.7f);
  // A camera like the reference one (45 degrees, 1080 pixels high), 10 reference distances from the
  // centre, draws about a tenth.
  ViewCamera camera;
  camera.eye = creatureCenter(m.rest) + Eigen::Vector3f(10.0f * d, 0, 0);
  const FurView v = makeFurView(FurParams{}, m.rest, camera);
  EXPECT_NEAR(cullingFactor(v), 10.0f, 1e-4f);
  const FurFrame far = test::furFrame(m.skin, r, p, m.rest, v);
  EXPECT_NEAR(static_cast<double>(far.coats[0].drawn),
              static_cast<double>(r.coats[0].size()) / 10.0,
              5 * std::sqrt(m.skin.numTriangles() * 0.25));
}

// The monkey: hairs per unit area are the same in small and large triangles (no bald small
// triangles), and hairs avoid the bare eyes.
TEST(RootsOnMonkey, DensityIsUniformAcrossTriangleSizes) {
  // The paper's default count, ~100,000 hairs: "less than one hair per triangle on average".
  const test::MonkeySkin& m = test::monkeySkin();
  const skin::SkinMesh& s = m.skin;
  constexpr double N = 100000;
  const FurParams p = test::simpleParams(HairStyle::Polyline, N);
  const FurRoots r = growRoots(s, p);
  const std::vector<double> area = triangleAreas(s);
  std::vector<std::int32_t> order;
  for (std::int32_t t = 0; t < s.numTriangles(); ++t)
    if (triangleHasFur(s, s.furLengths(), t)) order.push_back(t);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return area[static_cast<std::size_t>(a)] < area[static_cast<std::size_t>(b)];
  });
  const double density = N / r.furredArea;
  const std::size_t q = order.size() / 4;
  for (int quart = 0; quart < 4; ++quart) {
    double a = 0.0, hairs = 0.0;
    for (std::size_t k = q * static_cast<std::size_t>(quart);
         k < q * static_cast<std::size_t>(quart + 1); ++k) {
      const auto t = static_cast<std::size_t>(order[k]);
      a += area[t];
      hairs += r.coats[0].triangleStart[t + 1] - r.coats[0].triangleStart[t];
    }
    // Random rounding: counts sum to the expectation, sd <= sqrt(q / 4) hairs per quartile.
    const double sd = std::sqrt(static_cast<double>(q) * 0.25) / (a * density);
    EXPECT_NEAR(hairs / a / density, 1.0, 5 * sd)
        << "area quartile " << quart << " (" << a << " m^2)";
    if (quart == 0) {
      EXPECT_LT(a * density / static_cast<double>(q), 1.0)
          << "small triangles average under one hair";
    }
  }
  EXPECT_NEAR(static_cast<double>(r.coats[0].size()), N,
              5 * std::sqrt(static_cast<double>(order.size()) * 0.25));
}

}  // namespace
}  // namespace pelage::fur
