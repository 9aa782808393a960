// Per-frame fur (generate.h) on small skins: the kernels equal the scalar reference bit for bit,
// the output does not depend on the thread count or the SIMD path, buffer layout and reuse.
// The same checks on the default monkey are in monkey_fur_test.cpp (slow).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pelage/fur/generate.h"
#include "pelage/fur/preset.h"
#include "pelage/util/parallel.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

TEST(Generate, KernelTargetsAreTheCpusBestFirstAndEachCanBeForced) {
  const std::vector<std::string> targets = kernelTargets();
  std::string names;
  for (const std::string& t : targets) names += " " + t;
  std::printf("kernel targets:%s\n", names.c_str());
  ASSERT_FALSE(targets.empty());
  // Named as users know them: Highway's AVX3 family is AVX-512.
  for (const std::string& t : targets) EXPECT_EQ(t.find("AVX3"), std::string::npos) << t;
  const auto has = [&](const char* name) {
    return std::find(targets.begin(), targets.end(), name) != targets.end();
  };
#if defined(__aarch64__)
  EXPECT_TRUE(has("NEON")) << names;  // every aarch64 CPU has NEON
#elif defined(__x86_64__)
  EXPECT_TRUE(has("SSE4") || has("SCALAR")) << names;
#endif
  EXPECT_EQ(activeKernelTarget(), targets.front());
  for (const std::string& t : targets) {
    ASSERT_TRUE(setKernelTarget(t)) << t;
    EXPECT_EQ(activeKernelTarget(), t);
  }
  EXPECT_FALSE(setKernelTarget("NO_SUCH_TARGET"));
  EXPECT_EQ(activeKernelTarget(), targets.back());  // unchanged
  ASSERT_TRUE(setKernelTarget("auto"));
  EXPECT_EQ(activeKernelTarget(), targets.front());
}

TEST(Generate, EveryStyleMatchesTheReferenceAndIsDeterministic) {
  // A small curved skin (normals in every direction, varying lengths, a bare-direction cap).
  const skin::SkinMesh s = test::makeSphere(0.1f, 24, 48);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  test::checkStylesAgainstReference(s, d, 6000, Eigen::Vector3f(0.0f, 0.0f, 0.1f));
}

TEST(Generate, CombedHairsMatchTheReferenceOnEveryPath) {
  // A groom's comb (groom.h) on the sphere: at each vertex a tangent direction of its own times an
  // amount in [0, 1] (every fourth vertex uncombed), so SIMD blocks mix combed, partly combed and
  // uncombed hairs; every kernel target equals the scalar reference bit for bit.
  const skin::SkinMesh s = test::makeSphere(0.1f, 24, 48);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  Groom groom;
  groom.vertex.comb.resize(static_cast<std::size_t>(s.numVertices()));
  for (std::size_t v = 0; v < groom.vertex.comb.size(); ++v) {
    const Eigen::Vector3f& n = d.normals[v];
    const Eigen::Vector3f any(std::sin(0.7f * static_cast<float>(v)),
                              std::cos(1.3f * static_cast<float>(v)), 0.5f);
    const float amount = v % 4 == 0 ? 0.0f : static_cast<float>(v % 7) / 6.0f;
    groom.vertex.comb[v] = amount * n.cross(any).normalized();
  }
  test::checkStylesAgainstReference(s, d, 6000, Eigen::Vector3f(0.0f, 0.0f, 0.1f), groom);
}

TEST(Generate, ACombLaysHairsAlongItAndLeavesUncombedHairsAsTheyWere) {
  // A flat grid, normal +Z, no segment direction: uncombed hairs stand straight up. Combed +X with
  // amount 1 on the right half, the weightless direction is +X; a horizontal hair has cos(theta) =
  // 0, so gravity leaves it (sec. 3.5) and the line lies along +X. Hairs on triangles whose three
  // vertices are uncombed are bit-identical to those of the fur without a groom.
  const skin::SkinMesh s = test::makeGrid(8, 0.01f, 0.01f);
  FurParams p = test::simpleParams(HairStyle::Line, 4000);
  Groom groom;
  groom.vertex.comb.assign(static_cast<std::size_t>(s.numVertices()), Eigen::Vector3f::Zero());
  for (int v = 0; v < s.numVertices(); ++v)
    if (s.restPositions()[3 * v] > 0.045f)
      groom.vertex.comb[static_cast<std::size_t>(v)] = Eigen::Vector3f::UnitX();
  const test::RestFur plain = test::restFur(s, p);
  const FurRoots combed = growRoots(s, p, groom);
  ASSERT_EQ(combed.coats[0].triangle, plain.roots.coats[0].triangle);
  const FurFrame fa = test::furFrame(s, plain.roots, p, plain.rest);
  const FurFrame fb = test::furFrame(s, combed, p, plain.rest);
  const HairBuffers &a = fa.coats[0], &b = fb.coats[0];
  int along = 0, same = 0;
  for (std::int64_t h = 0; h < b.drawn; ++h) {
    const std::int32_t* tv = s.triangles.data() + 3 * combed.coats[0].triangle[h];
    int combedVertices = 0;
    for (int k = 0; k < 3; ++k)
      combedVertices += groom.vertex.comb[static_cast<std::size_t>(tv[k])].x() > 0.0f ? 1 : 0;
    const Eigen::Vector3f chord = test::point(b, h, 1) - test::point(b, h, 0);
    if (combedVertices == 3) {
      EXPECT_GT(chord.x() / chord.norm(), 0.99999f) << "hair " << h;
      ++along;
    } else if (combedVertices == 0) {
      EXPECT_EQ(test::point(b, h, 1), test::point(a, h, 1)) << "hair " << h;
      ++same;
    }
  }
  EXPECT_GT(along, 1000);
  EXPECT_GT(same, 1000);
}

TEST(Generate, FrizzMatchesTheReferenceOnEveryPathAndKeepsTheRoots) {
  // Frizz (fur_params.h Frizz) on the sphere, every style: each kernel target and thread count
  // equals the scalar reference bit for bit; strand point 0 (every point of a tube's first ring)
  // is where it is without frizz, and every other point moved by at most amplitude t^w per axis.
  // Amplitude 0 with other frizz fields set gives today's hairs exactly.
  const skin::SkinMesh s = test::makeSphere(0.1f, 16, 32);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    FurParams base = test::simpleParams(style, 2000);
    base.coats[0].segmentDirectionWeight = 0.4f;
    FurParams plain = base;
    plain.coats[0].frizz.frequency = 3.5f;
    plain.coats[0].frizz.tipWeight = 1.5f;
    FurParams p = plain;
    p.coats[0].frizz.amplitudeMm = 1.0f;
    const FurRoots r = growRoots(s, p);
    const FurFrame without = test::furFrame(s, r, plain, d);
    EXPECT_TRUE(test::sameHairs(without, test::furFrame(s, r, base, d)))
        << "amplitude 0: the hairs of no frizz";
    setThreadCount(1);
    const FurFrame one = test::furFrame(s, r, p, d);
    setThreadCount(2);
    EXPECT_TRUE(test::sameHairs(one, test::furFrame(s, r, p, d)));
    setThreadCount(0);
    const HairBuffers &a = without.coats[0], &b = one.coats[0];
    const int M = b.layout.ringSides, K = b.layout.strandPoints;
    std::vector<float> pos, nrm;
    for (std::int64_t h = 0; h < b.drawn; ++h) {
      for (int k = 0; k < K; ++k) {
        const float bound = 1e-3f * std::pow(k / float(K - 1), 1.5f) * 1.0001f + 1e-7f;
        for (int m = 0; m < M; ++m) {
          const Eigen::Vector3f moved = test::point(b, h, k * M + m) - test::point(a, h, k * M + m);
          if (k == 0) {
            ASSERT_EQ(moved, Eigen::Vector3f::Zero()) << "hair " << h;
          }
          ASSERT_LE(moved.cwiseAbs().maxCoeff(), bound) << "hair " << h << " point " << k;
        }
      }
      if (h % 3 != 0) continue;
      referenceHair(s, r, p, d, 0, h, pos, nrm);
      const std::size_t n = static_cast<std::size_t>(b.layout.pointsPerHair()) * 3;
      ASSERT_EQ(0, std::memcmp(pos.data(), b.positions.data() + static_cast<std::size_t>(h) * n,
                               n * sizeof(float)))
          << "hair " << h;
    }
    for (const std::string& target : kernelTargets()) {
      ASSERT_TRUE(setKernelTarget(target));
      EXPECT_TRUE(test::sameHairs(one, test::furFrame(s, r, p, d))) << target;
    }
    setKernelTarget("auto");
  }
}

TEST(Generate, ClumpedHairsGatherByTheStrengthAndMatchTheReferenceOnEveryPath) {
  // Clumping (fur_params.h Clump) on the sphere, every style: each clumped hair's strand point k
  // lies (1 - s_k) of the way it did from its centre hair's, s_k = strength t^shape, so the tips'
  // mean distance to their centres' tips falls by exactly the strength; the roots, the centres
  // and the hairs in no clump stay bit for bit. Each kernel target and thread count equals the
  // scalar reference bit for bit, and a culled frame draws the same clumped hairs.
  const skin::SkinMesh s = test::makeSphere(0.1f, 16, 32);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    FurParams plain = test::simpleParams(style, 3000);
    plain.coats[0].segmentDirectionWeight = 0.4f;
    plain.coats[0].clump = {.density = 0.2f, .strength = 0.0f, .shape = 1.5f, .radiusMm = 25.0f};
    FurParams p = plain;
    p.coats[0].clump.strength = 0.6f;
    const FurRoots r = growRoots(s, p);
    const CoatRoots& cr = r.coats[0];
    ASSERT_EQ(cr.clumpSlot.size(), static_cast<std::size_t>(cr.size()));
    // The coat clumps with these roots and a strength; not with strength 0, nor with roots grown
    // without clumps.
    EXPECT_TRUE(coatClumps(p, r, 0));
    EXPECT_FALSE(coatClumps(plain, r, 0));
    EXPECT_FALSE(coatClumps(p, growRoots(s, plain), 0));
    const FurFrame without = test::furFrame(s, r, plain, d);  // strength 0: off
    setThreadCount(1);
    const FurFrame one = test::furFrame(s, r, p, d);
    setThreadCount(2);
    EXPECT_TRUE(test::sameHairs(one, test::furFrame(s, r, p, d)));
    setThreadCount(0);
    const HairBuffers &a = without.coats[0], &b = one.coats[0];
    const int K = b.layout.strandPoints, P = b.layout.pointsPerHair();
    double before = 0.0, after = 0.0;
    std::int64_t clumped = 0;
    std::vector<float> pos, nrm;
    for (std::int64_t h = 0; h < b.drawn; ++h) {
      const std::int32_t slot = cr.clumpSlot[static_cast<std::size_t>(h)];
      const std::int64_t c = slot < 0 ? h : cr.clumpCentres[static_cast<std::size_t>(slot)];
      if (c == h) {
        for (int i = 0; i < P; ++i) ASSERT_EQ(test::point(b, h, i), test::point(a, h, i)) << h;
        continue;
      }
      ++clumped;
      for (int m = 0; m < b.layout.ringSides; ++m)
        ASSERT_EQ(test::point(b, h, m), test::point(a, h, m)) << "root of hair " << h;
      for (int k = 1; k < K; ++k) {
        const float sk = 0.6f * std::pow(k / float(K - 1), 1.5f);
        const Eigen::Vector3f C = test::strandPoint(a, c, k);
        const Eigen::Vector3f expected = C + (1.0f - sk) * (test::strandPoint(a, h, k) - C);
        ASSERT_LE((test::strandPoint(b, h, k) - expected).norm(), 2e-6f)
            << "hair " << h << " k " << k;
      }
      before += (test::strandPoint(a, h, K - 1) - test::strandPoint(a, c, K - 1)).norm();
      after += (test::strandPoint(b, h, K - 1) - test::strandPoint(a, c, K - 1)).norm();
      if (h % 3 != 0) continue;
      referenceHair(s, r, p, d, 0, h, pos, nrm);
      const std::size_t n = static_cast<std::size_t>(P) * 3;
      ASSERT_EQ(0, std::memcmp(pos.data(), b.positions.data() + static_cast<std::size_t>(h) * n,
                               n * sizeof(float)))
          << "hair " << h;
    }
    EXPECT_GT(clumped, b.drawn * 8 / 10);
    EXPECT_NEAR(after / before, 1.0 - 0.6, 1e-4);
    for (const std::string& target : kernelTargets()) {
      ASSERT_TRUE(setKernelTarget(target));
      EXPECT_TRUE(test::sameHairs(one, test::furFrame(s, r, p, d))) << target;
    }
    setKernelTarget("auto");
    // Culling draws a prefix of each triangle's roots; a drawn hair keeps its clump even where its
    // centre is not drawn.
    FurView far;
    far.culling = true;
    far.referenceDistance = 0.1f;
    far.viewDistance = 0.3f;
    const FurFrame culled = test::furFrame(s, r, p, d, far);
    const HairBuffers& cb = culled.coats[0];
    ASSERT_LT(cb.drawn, b.drawn);
    for (std::int64_t i = 0; i < cb.drawn; ++i) {
      const std::int64_t h = cb.hairIds[static_cast<std::size_t>(i)];
      for (int k = 0; k < P; ++k) ASSERT_EQ(test::point(cb, i, k), test::point(b, h, k)) << h;
    }
  }
}

TEST(Generate, AGroomsClumpScaleMultipliesTheStrengthPerHair) {
  // The groom's per-vertex clump scale (groom.h), interpolated at each root: a hair's strand
  // points lie (1 - scale s_k) of the way from its centre's; scale 0 leaves it as unclumped, bit
  // for bit; the kernel equals the reference.
  const skin::SkinMesh s = test::makeSphere(0.1f, 16, 32);
  skin::DeformedSkin d;
  skin::restSkin(s, d);
  FurParams p = test::simpleParams(HairStyle::Polyline, 3000);
  p.coats[0].clump = {.density = 0.2f, .strength = 0.6f, .shape = 1.0f, .radiusMm = 25.0f};
  FurParams plain = p;
  plain.coats[0].clump.strength = 0.0f;
  Groom groom;
  const float* rest = s.restPositions();
  for (int v = 0; v < s.numVertices(); ++v)  // 0 on the lower half, rising to 1 at the top
    groom.vertex.clump.push_back(std::clamp(rest[3 * v + 2] / 0.1f, 0.0f, 1.0f));
  const FurRoots r = growRoots(s, p, groom);
  const CoatRoots& cr = r.coats[0];
  ASSERT_EQ(cr.clumpScale.size(), static_cast<std::size_t>(cr.size()));
  const FurFrame a = test::furFrame(s, r, plain, d), b = test::furFrame(s, r, p, d);
  const HairBuffers &ha = a.coats[0], &hb = b.coats[0];
  const int K = hb.layout.strandPoints;
  std::int64_t still = 0, pulled = 0;
  std::vector<float> pos, nrm;
  for (std::int64_t h = 0; h < hb.drawn; ++h) {
    const std::int32_t slot = cr.clumpSlot[static_cast<std::size_t>(h)];
    const std::int64_t c = slot < 0 ? h : cr.clumpCentres[static_cast<std::size_t>(slot)];
    const float scale = cr.clumpScale[static_cast<std::size_t>(h)];
    if (c == h) continue;
    if (scale == 0.0f) {
      ++still;
      for (int k = 0; k < K; ++k) ASSERT_EQ(test::point(hb, h, k), test::point(ha, h, k)) << h;
      continue;
    }
    pulled += scale > 0.5f;
    for (int k = 1; k < K; ++k) {
      const float sk = 0.6f * (k / float(K - 1)) * scale;
      const Eigen::Vector3f C = test::point(ha, c, k);
      const Eigen::Vector3f expected = C + (1.0f - sk) * (test::point(ha, h, k) - C);
      ASSERT_LE((test::point(hb, h, k) - expected).norm(), 2e-6f) << "hair " << h << " k " << k;
    }
    if (h % 4 != 0) continue;
    referenceHair(s, r, p, d, 0, h, pos, nrm);
    const std::size_t n = static_cast<std::size_t>(hb.layout.pointsPerHair()) * 3;
    ASSERT_EQ(0, std::memcmp(pos.data(), hb.positions.data() + static_cast<std::size_t>(h) * n,
                             n * sizeof(float)))
        << "hair " << h;
  }
  EXPECT_GT(still, hb.drawn / 4);
  EXPECT_GT(pulled, hb.drawn / 10);
}

TEST(Generate, FrizzAtTheTipIsUniformNoiseOfTheAmplitude) {
  // Lines (two points): the tip's offset is amplitude g, g the lattice vector at t f = 4 exactly
  // (blend 0), uniform in [-1, 1)^3 per hair: mean 0 and variance amplitude^2 / 3 per axis, axes
  // uncorrelated, a flat histogram within [-1, 1] (n = 20,000 hairs; bounds at 5 standard errors).
  const skin::SkinMesh s = test::makeGrid(16, 0.01f, 0.01f);
  FurParams plain = test::simpleParams(HairStyle::Line, 20000);
  FurParams p = plain;
  p.coats[0].frizz = {.amplitudeMm = 2.0f, .frequency = 4.0f, .tipWeight = 3.0f};
  const test::RestFur rf = test::restFur(s, p);
  const FurFrame a = test::furFrame(s, rf.roots, plain, rf.rest);
  const FurFrame b = test::furFrame(s, rf.roots, p, rf.rest);
  const std::int64_t n = b.coats[0].drawn;
  ASSERT_GT(n, 19000);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
  double xy = 0.0, largest = 0.0;
  std::array<int, 10> bins{};  // the x offset's histogram over [-1, 1)
  for (std::int64_t h = 0; h < n; ++h) {
    const Eigen::Vector3d o =
        ((test::point(b.coats[0], h, 1) - test::point(a.coats[0], h, 1)) / 2e-3f).cast<double>();
    sum += o;
    sq += o.cwiseProduct(o);
    xy += o.x() * o.y();
    largest = std::max(largest, o.cwiseAbs().maxCoeff());
    ++bins[static_cast<std::size_t>(std::clamp(static_cast<int>((o.x() + 1.0) * 5.0), 0, 9))];
  }
  const double N = static_cast<double>(n);
  // Within the amplitude (up to float rounding of the point), and reaching it.
  EXPECT_LE(largest, 1.0 + 1e-3);
  EXPECT_GT(largest, 0.99);
  for (int bin : bins) EXPECT_NEAR(bin / N, 0.1, 5.0 * std::sqrt(0.09 / N));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(sum[k] / N, 0.0, 5.0 * std::sqrt(1.0 / 3.0 / N)) << "axis " << k;
    // Var of U^2 for U uniform on [-1, 1]: 1/5 - 1/9 = 4/45.
    EXPECT_NEAR(sq[k] / N, 1.0 / 3.0, 5.0 * std::sqrt(4.0 / 45.0 / N)) << "axis " << k;
  }
  EXPECT_NEAR(xy / N, 0.0, 5.0 * std::sqrt(1.0 / 9.0 / N));
}

TEST(Generate, PackedCombsRoundTripWithinHalfAStep) {
  for (const auto& [x, y] : std::vector<std::pair<float, float>>{
           {0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, -1.0f}, {0.6f, -0.8f}, {-0.123f, 0.456f}}) {
    float u = 2.0f, w = 2.0f;
    unpackComb(packComb(x, y), u, w);
    EXPECT_NEAR(u, x, 0.5f / 32767.0f);
    EXPECT_NEAR(w, y, 0.5f / 32767.0f);
  }
  float u = 2.0f, w = 2.0f;
  unpackComb(packComb(0.0f, 0.0f), u, w);
  EXPECT_EQ(u, 0.0f);  // no comb: exactly 0, so d is kept exactly
  EXPECT_EQ(w, 0.0f);
  EXPECT_EQ(packComb(0.0f, 0.0f), 0u);
  unpackComb(packComb(1.0f, -1.0f), u, w);
  EXPECT_EQ(u, 1.0f);
  EXPECT_EQ(w, -1.0f);
}

TEST(Generate, DegenerateHairPlanesMatchTheReferenceOnEveryPath) {
  // Sec. 3.7 fallbacks inside SIMD blocks: on the left half of a flat grid the vertices have no
  // segment direction, so with no end randomize the hairs stand straight up (d~ = n = U, e = U):
  // R, W and E are collinear and the hair plane (and the tube's ring frame) take their fallbacks;
  // on the right half (direction +X) the planes are regular. Blocks mix both kinds of hair, and
  // every kernel target must still equal the scalar reference bit for bit.
  skin::SkinMesh s = test::makeGrid(12, 0.01f, 0.01f, Eigen::Vector3f(1, 0, 0));
  for (auto v : s.mesh.vertices())
    if (s.mesh.point(v)[0] < 0.055f)
      s.mesh.property(s.segmentDirection, v) = OpenMesh::Vec3f(0, 0, 0);
  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    FurParams p = test::simpleParams(style, 3000);
    p.coats[0].segmentDirectionWeight = 0.5f;
    p.coats[0].normalRandomize = 0.3f;
    const test::RestFur rf = test::restFur(s, p);
    std::int64_t degenerate = 0;
    for (const std::string& target : kernelTargets()) {
      ASSERT_TRUE(setKernelTarget(target));
      SCOPED_TRACE(target);
      const FurFrame f = test::furFrame(s, rf.roots, p, rf.rest);
      const HairBuffers& hb = f.coats[0];
      ASSERT_GT(hb.drawn, 2500);
      const std::size_t n = static_cast<std::size_t>(hb.layout.pointsPerHair()) * 3;
      std::vector<float> pos, nrm;
      degenerate = 0;
      for (std::int64_t h = 0; h < hb.drawn; ++h) {
        referenceHair(s, rf.roots, p, rf.rest, 0, h, pos, nrm);
        ASSERT_EQ(0, std::memcmp(pos.data(), hb.positions.data() + static_cast<std::size_t>(h) * n,
                                 n * sizeof(float)))
            << "hair " << h;
        ASSERT_EQ(0, std::memcmp(nrm.data(), hb.normals.data() + static_cast<std::size_t>(h) * n,
                                 n * sizeof(float)))
            << "hair " << h;
        const Eigen::Vector3f chord =
            test::point(hb, h, hb.layout.pointsPerHair() - 1) - test::point(hb, h, 0);
        if (chord.x() == 0.0f && chord.y() == 0.0f) ++degenerate;
      }
    }
    setKernelTarget("auto");
    if (style != HairStyle::Tube) {  // (a tube's last ring is around the end, not at it)
      EXPECT_GT(degenerate, 1000) << "hairs straight up on the bare half";
      EXPECT_LT(degenerate, 2000) << "hairs leaning along +X on the other half";
    }
  }
}

TEST(Generate, PolylineEndsAtDistanceLFromTheRoot) {
  const skin::SkinMesh s = test::makeGrid(8, 0.01f, 0.02f, Eigen::Vector3f(1, 0, 0));
  FurParams p = test::simpleParams(HairStyle::Polyline, 3000);
  p.coats[0].segmentDirectionWeight = 0.4f;
  p.coats[0].hairEndRandomize = 0.3f;
  p.coats[0].normalRandomize = 0.4f;
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  const FurFrame f = test::furFrame(s, r, p, d);
  FurParams stiff = p;
  stiff.coats[0].stiffness = 1.0f;  // f = 0.02
  const FurFrame g = test::furFrame(s, r, stiff, d);
  const HairBuffers& hb = f.coats[0];
  ASSERT_GT(hb.drawn, 2500);
  for (std::int64_t h = 0; h < hb.drawn; ++h) {
    EXPECT_NEAR((test::point(hb, h, 7) - test::point(hb, h, 0)).norm(), 0.02f, 1e-8f);
    EXPECT_EQ(test::point(hb, h, 0).z(), 0.0f) << "roots lie on the skin";
    EXPECT_LT(test::point(hb, h, 7).z(), test::point(g.coats[0], h, 7).z())
        << "gravity lowers the end";
  }
}

TEST(Generate, FrameBuffersAreReusedWithoutReallocation) {
  const skin::SkinMesh s = test::makeGrid(8, 0.01f, 0.02f);
  const FurParams p = test::simpleParams(HairStyle::Polyline, 2000);
  const test::RestFur rf = test::restFur(s, p);
  const FurRoots& r = rf.roots;
  const skin::DeformedSkin& d = rf.rest;
  FurWorkspace ws;
  FurFrame f;
  generateFur(s, r, p, d, {}, ws, f);
  const float* pos = f.coats[0].positions.data();
  const float* records = ws.vertexRecords.data();
  FurView far;
  far.culling = true;
  far.viewDistance = 4.0f;
  for (int k = 0; k < 3; ++k) generateFur(s, r, p, d, k == 1 ? far : FurView{}, ws, f);
  EXPECT_EQ(f.coats[0].positions.data(), pos);
  EXPECT_EQ(ws.vertexRecords.data(), records);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(pos) % 64, 0u) << "aligned for streaming stores";
}

TEST(Generate, PointsPerHairPerStyle) {
  CoatParams c;
  c.style = HairStyle::Line;
  EXPECT_EQ(pointsPerHair(c), 2);
  c.style = HairStyle::Polyline;
  EXPECT_EQ(pointsPerHair(c), 8);
  c.style = HairStyle::Curve;
  c.curvePoints = 12;
  EXPECT_EQ(pointsPerHair(c), 12);
  c.style = HairStyle::Tube;
  c.tubeSides = 5;
  EXPECT_EQ(pointsPerHair(c), 60);
}

}  // namespace
}  // namespace pelage::fur
