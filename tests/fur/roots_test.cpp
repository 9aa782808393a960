// Hair roots (Van Gelder & Wilhelms 1997, sec. 3.2): the barycentric table, random rounding, the
// spatial distribution over a triangle and over the whole monkey, coats, budgets.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "pelage/fur/roots.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "pelage/util/random.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

using test::makeGrid;
using test::makeSkin;

TEST(Roots, BarycentricTableIsValid) {
  const std::vector<float> t = makeBarycentricTable(42);
  ASSERT_EQ(t.size(), static_cast<std::size_t>(kBarycentricTableSize) * 4);
  for (int j = 0; j < kBarycentricTableSize; ++j) {
    const float* b = t.data() + 4 * j;
    EXPECT_GE(b[0], 0.0f);
    EXPECT_GE(b[1], 0.0f);
    EXPECT_GE(b[2], -1e-7f);
    EXPECT_NEAR(b[0] + b[1] + b[2], 1.0f, 2e-7f);
  }
  EXPECT_EQ(makeBarycentricTable(42), t) << "same seed, same table";
  EXPECT_NE(makeBarycentricTable(43), t);
}

// Index of the sub-triangle (of 16 congruent ones, each 1/16 of the area) holding barycentric b.
int subTriangle(const float* b) {
  const int i = std::min(3, static_cast<int>(b[0] * 4)),
            j = std::min(3, static_cast<int>(b[1] * 4));
  const int k = std::min(3, static_cast<int>(b[2] * 4));
  const bool upright = i + j + k == 3;  // 10 upright, 6 inverted cells
  return upright ? i * 4 + j : 16 + i * 3 + j;
}

TEST(Roots, TablePointsAreUniformOverTheTriangle) {
  // sec. 3.2: b1 = 1 - sqrt(u1), b2 = (1 - b1) u2 gives a uniform 2D distribution. Chi-square of
  // the 2048 entries over 16 equal-area cells, 15 degrees of freedom: 37.7 is the 0.1% point.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<float> t = makeBarycentricTable(seed);
    std::map<int, int> cells;
    for (int j = 0; j < kBarycentricTableSize; ++j) ++cells[subTriangle(t.data() + 4 * j)];
    ASSERT_EQ(cells.size(), 16u) << "every cell hit";
    const double expected = kBarycentricTableSize / 16.0;
    double chi2 = 0.0;
    for (const auto& [cell, n] : cells) chi2 += (n - expected) * (n - expected) / expected;
    EXPECT_LT(chi2, 37.7) << "seed " << seed;
  }
  // b1 alone has the triangular density 2 (1 - b1): mean 1/3.
  const std::vector<float> t = makeBarycentricTable(5);
  double mean = 0.0;
  for (int j = 0; j < kBarycentricTableSize; ++j) mean += t[static_cast<std::size_t>(4 * j)];
  mean /= kBarycentricTableSize;
  EXPECT_NEAR(mean, 1.0 / 3.0, 4 * std::sqrt(1.0 / 18.0 / kBarycentricTableSize));
}

TEST(Roots, RandomRoundingIsUnbiased) {
  // 40 x 40 x 2 = 3200 equal triangles and N = 960 hairs: alpha N = 0.3 on every triangle.
  // Deterministic rounding would give 0 hairs; floor(alpha N + u) gives 960 on average with
  // standard deviation sqrt(3200 * 0.3 * 0.7) = 25.9.
  const skin::SkinMesh s = makeGrid(40, 0.01f, 0.01f);
  FurParams p = test::simpleParams(HairStyle::Line, 960);
  double sum = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    p.seed = seed;
    const FurRoots r = growRoots(s, p);
    EXPECT_NEAR(static_cast<double>(r.coats[0].size()), 960.0, 5 * 25.9) << seed;
    sum += static_cast<double>(r.coats[0].size());
    for (std::int32_t t = 0; t < s.numTriangles(); ++t) {
      const std::int32_t k = r.coats[0].triangleStart[static_cast<std::size_t>(t) + 1] -
                             r.coats[0].triangleStart[static_cast<std::size_t>(t)];
      ASSERT_TRUE(k == 0 || k == 1) << "floor(0.3 + u) is 0 or 1";
    }
  }
  EXPECT_NEAR(sum / 10.0, 960.0, 5 * 25.9 / std::sqrt(10.0));
}

TEST(Roots, RootsAreGroupedByTriangleInCreationOrderCyclingTheTable) {
  const skin::SkinMesh s = makeGrid(10, 0.01f, 0.01f);
  FurParams p = test::simpleParams(HairStyle::Polyline, 5000);
  p.undercoatShare = 0.25f;
  const FurRoots r = growRoots(s, p);
  EXPECT_EQ(r.triangleCount, s.numTriangles());
  EXPECT_NEAR(r.furredArea, 0.01, 1e-8);
  for (int c = 0; c < kCoatCount; ++c) {
    const CoatRoots& cr = r.coats[static_cast<std::size_t>(c)];
    ASSERT_EQ(cr.triangleStart.size(), static_cast<std::size_t>(s.numTriangles()) + 1);
    EXPECT_EQ(cr.triangleStart.front(), 0);
    EXPECT_EQ(cr.triangleStart.back(), cr.size());
    EXPECT_EQ(cr.tableIndex.size(), cr.triangle.size());
    EXPECT_EQ(cr.jitter.size(), 4 * cr.triangle.size());
    for (std::int32_t t = 0; t < s.numTriangles(); ++t)
      for (std::int32_t k = cr.triangleStart[static_cast<std::size_t>(t)];
           k < cr.triangleStart[static_cast<std::size_t>(t) + 1]; ++k) {
        EXPECT_EQ(cr.triangle[static_cast<std::size_t>(k)], t);
        EXPECT_EQ(cr.tableIndex[static_cast<std::size_t>(k)], k % kBarycentricTableSize);
      }
    for (std::size_t k = 0; k < cr.triangle.size(); ++k) {
      const Eigen::Vector3f xi(cr.jitter[4 * k], cr.jitter[4 * k + 1], cr.jitter[4 * k + 2]);
      EXPECT_LE(xi.norm(), 1.0f + 1e-6f);
      EXPECT_GE(cr.jitter[4 * k + 3], 0.0f);
      EXPECT_LT(cr.jitter[4 * k + 3], 1.0f);
    }
  }
  // Coats split N as N (1 - share) and N share, each rounded per triangle.
  EXPECT_DOUBLE_EQ(r.coats[0].expectedHairs, 3750.0);
  EXPECT_DOUBLE_EQ(r.coats[1].expectedHairs, 1250.0);
  EXPECT_NEAR(static_cast<double>(r.coats[0].size()), 3750.0, 5 * std::sqrt(200 * 0.25));
  EXPECT_NEAR(static_cast<double>(r.coats[1].size()), 1250.0, 5 * std::sqrt(200 * 0.25));
  EXPECT_NE(r.coats[0].jitter, r.coats[1].jitter) << "the coats use their own random streams";
}

TEST(Roots, HairEndJitterIsUniformInTheUnitBall) {
  // Radius: P(|xi| <= rho) = rho^3, so |xi|^3 is uniform; directions: each axis mean 0.
  const skin::SkinMesh s = makeGrid(20, 0.01f, 0.01f);
  const FurRoots r = growRoots(s, test::simpleParams(HairStyle::Line, 20000));
  const CoatRoots& cr = r.coats[0];
  const std::size_t n = cr.triangle.size();
  int bins[10] = {};
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d xi(cr.jitter[4 * k], cr.jitter[4 * k + 1], cr.jitter[4 * k + 2]);
    ++bins[std::min(9, static_cast<int>(std::pow(xi.norm(), 3) * 10))];
    mean += xi;
  }
  const double expected = static_cast<double>(n) / 10.0;
  double chi2 = 0.0;
  for (int b : bins) chi2 += (b - expected) * (b - expected) / expected;
  EXPECT_LT(chi2, 27.9) << "9 degrees of freedom, 0.1% point";
  mean /= static_cast<double>(n);
  EXPECT_LT(mean.norm(), 5 * std::sqrt(0.2 / static_cast<double>(n)));  // var of a coordinate = 1/5
}

TEST(Roots, BareTrianglesGetNoHairsAndDoNotCountInTheArea) {
  // Two unit triangles; the second's vertices have no fur. All hairs go to the first, and the
  // density per furred area is N / 0.5.
  std::vector<Eigen::Vector3f> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                    {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  skin::SkinMesh s = makeSkin(v, {{0, 1, 2}, {3, 4, 5}}, 0.01f);
  for (int k = 3; k < 6; ++k) s.mesh.property(s.furLength, skin::TriMesh::VertexHandle(k)) = 0.0f;
  FurParams p = test::simpleParams(HairStyle::Line, 1000);
  const FurRoots r = growRoots(s, p);
  EXPECT_DOUBLE_EQ(r.furredArea, 0.5);
  EXPECT_EQ(r.coats[0].size(), 1000);
  EXPECT_EQ(r.coats[0].triangleStart[2] - r.coats[0].triangleStart[1], 0);
  // A density gives N = density * furred area.
  p.densityPerM2 = 3000;
  EXPECT_EQ(growRoots(s, p).coats[0].size(), 1500);
}

TEST(Roots, AbsurdCountsAreRefusedWithTheMemoryNeeded) {
  const skin::SkinMesh s = makeGrid(2, 1.0f, 0.01f);
  FurParams p = test::simpleParams(HairStyle::Polyline, 2e10);
  try {
    growRoots(s, p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("2e+10 hairs"), std::string::npos) << m;
    EXPECT_NE(m.find("TB"), std::string::npos) << m;
    EXPECT_NE(m.find("accepted: 0 to 2e+07"), std::string::npos) << m;
  }
  p.setHairCount(1e6);
  p.densityPerM2 = 1e10;  // over 4 m^2
  EXPECT_THROW(growRoots(s, p), InputError);
  // Within the count but over the memory: 2e7 tubes of 64 x 32 points.
  FurParams t = test::simpleParams(HairStyle::Tube, 2e7);
  for (auto& c : t.coats) {
    c.curvePoints = 64;
    c.tubeSides = 32;
  }
  EXPECT_THROW(checkHairBudget(t, 1.0), InputError);
  EXPECT_NO_THROW(checkHairBudget(test::simpleParams(HairStyle::Polyline, 5e5), 1.0));
}

TEST(Roots, SameSeedSameRootsAnyThreadCount) {
  const skin::SkinMesh s = makeGrid(30, 0.01f, 0.01f);
  FurParams p = test::simpleParams(HairStyle::Line, 30000);
  p.undercoatShare = 0.5f;
  setThreadCount(1);
  const FurRoots a = growRoots(s, p);
  setThreadCount(3);
  const FurRoots b = growRoots(s, p);
  setThreadCount(0);
  for (int c = 0; c < kCoatCount; ++c) {
    EXPECT_EQ(a.coats[static_cast<std::size_t>(c)].triangleStart,
              b.coats[static_cast<std::size_t>(c)].triangleStart);
    EXPECT_EQ(a.coats[static_cast<std::size_t>(c)].jitter,
              b.coats[static_cast<std::size_t>(c)].jitter);
  }
  p.seed = 2;
  EXPECT_NE(growRoots(s, p).coats[0].triangleStart, a.coats[0].triangleStart);
}

TEST(Roots, ClumpsAreTheLeastPriorityRootOfEachCubeAndRootsJoinTheNearestWithinTheRadius) {
  // 30 x 30 cm of skin at 1 clump per cm^2 (1 cm cubes), 20,000 roots: every cube the grid covers
  // has a centre; each root's clump checked by brute force (the nearest centre among the 27
  // cubes around its own, ties to the lower index, within the radius); the same whatever the
  // thread count.
  const skin::SkinMesh s = makeGrid(30, 0.01f, 0.01f);
  for (const float radiusMm : {25.0f, 4.0f}) {
    SCOPED_TRACE(radiusMm);
    FurParams p = test::simpleParams(HairStyle::Line, 20000);
    p.coats[0].clump = {.density = 1.0f, .strength = 0.5f, .shape = 1.0f, .radiusMm = radiusMm};
    setThreadCount(1);
    const FurRoots r = growRoots(s, p);
    setThreadCount(2);
    const FurRoots r2 = growRoots(s, p);
    setThreadCount(0);
    const CoatRoots& cr = r.coats[0];
    EXPECT_EQ(cr.clumpCentres, r2.coats[0].clumpCentres);
    EXPECT_EQ(cr.clumpSlot, r2.coats[0].clumpSlot);
    EXPECT_TRUE(r.coats[1].clumpSlot.empty()) << "the undercoat does not clump";
    ASSERT_GE(cr.clumpCentres.size(), 900u);
    ASSERT_LE(cr.clumpCentres.size(), 961u);
    const std::uint64_t seed = coatSeed(p.seed, 0);
    const auto cubeOf = [](const Eigen::Vector3f& x) {
      return std::array<long, 3>{static_cast<long>(std::floor(static_cast<double>(x.x()) / 0.01)),
                                 static_cast<long>(std::floor(static_cast<double>(x.y()) / 0.01)),
                                 static_cast<long>(std::floor(static_cast<double>(x.z()) / 0.01))};
    };
    std::map<std::array<long, 3>, std::int64_t> least;  // cube -> root of least priority
    for (std::int64_t k = 0; k < cr.size(); ++k) {
      const auto cube = cubeOf(restRootPosition(s, r.barycentric, cr, k));
      const auto it = least.find(cube);
      const auto u = [&](std::int64_t i) {
        return uniform01(seed, kStreamClump, static_cast<std::uint64_t>(i));
      };
      if (it == least.end() || u(k) < u(it->second)) least[cube] = k;
    }
    std::vector<std::int32_t> centres;
    for (const auto& [cube, k] : least) centres.push_back(static_cast<std::int32_t>(k));
    std::sort(centres.begin(), centres.end());
    ASSERT_EQ(cr.clumpCentres, centres);
    std::int64_t joined = 0;
    for (std::int64_t k = 0; k < cr.size(); ++k) {
      const Eigen::Vector3f x = restRootPosition(s, r.barycentric, cr, k);
      const auto cube = cubeOf(x);
      float best = std::numeric_limits<float>::infinity();
      std::int32_t expected = -1;
      for (std::size_t slot = 0; slot < centres.size(); ++slot) {
        const Eigen::Vector3f c = restRootPosition(s, r.barycentric, cr, centres[slot]);
        const auto cc = cubeOf(c);
        if (std::abs(cc[0] - cube[0]) > 1 || std::abs(cc[1] - cube[1]) > 1 ||
            std::abs(cc[2] - cube[2]) > 1)
          continue;
        const float d2 = (c - x).squaredNorm();
        if (d2 < best) best = d2, expected = static_cast<std::int32_t>(slot);
      }
      if (best > 1e-6f * radiusMm * radiusMm) expected = -1;
      ASSERT_EQ(cr.clumpSlot[static_cast<std::size_t>(k)], expected) << "root " << k;
      joined += expected >= 0;
    }
    // A 25 mm radius reaches every root's nearest centre; 4 mm leaves some out.
    if (radiusMm > 20.0f)
      EXPECT_EQ(joined, cr.size());
    else
      EXPECT_LT(joined, cr.size());
  }
  FurParams off = test::simpleParams(HairStyle::Line, 2000);
  off.coats[0].clump.density = 1.0f;
  off.coats[0].clump.strength = 0.0f;
  EXPECT_TRUE(growRoots(s, off).coats[0].clumpCentres.empty()) << "strength 0 is off";
}

}  // namespace
}  // namespace pelage::fur
