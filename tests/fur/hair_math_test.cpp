// The per-hair formulas of Van Gelder & Wilhelms 1997 sec. 3.2 to 3.8 (hair_math.h): hand-computed
// cases and properties under random inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pelage/fur/generate.h"
#include "pelage/fur/hair_math.h"

namespace pelage::fur {
namespace {

using V = Vec3<float>;

V v3(float x, float y, float z) {
  return {x, y, z};
}
Eigen::Vector3f E(const V& v) {
  return {v.x, v.y, v.z};
}
V fromE(const Eigen::Vector3f& v) {
  return {v.x(), v.y(), v.z()};
}

// Records the points of one hair.
struct Collect {
  std::vector<Eigen::Vector3f> p, n;
  void operator()(int i, const V& pos, const V& nrm) {
    if (p.size() <= static_cast<std::size_t>(i)) {
      p.resize(static_cast<std::size_t>(i) + 1);
      n.resize(static_cast<std::size_t>(i) + 1);
    }
    p[static_cast<std::size_t>(i)] = E(pos);
    n[static_cast<std::size_t>(i)] = E(nrm);
  }
};

CoatShape shapeFor(HairStyle style, float stiffness, float weight = 0.0f,
                   float endRandomize = 0.0f) {
  FurParams p;
  p.coats[0].style = style;
  p.coats[0].stiffness = stiffness;
  p.coats[0].segmentDirectionWeight = weight;
  p.coats[0].hairEndRandomize = endRandomize;
  return makeCoatShape(p, 0);
}

// One hair's inputs at its root (no groom values: those are zero).
HairInput<float> inputOf(const V& root, const V& n, const V& s, float length, const V& xi,
                         float phase) {
  HairInput<float> in{};
  in.root = root;
  in.normalSum = n;
  in.directionSum = s;
  in.length = length;
  in.xi = xi;
  in.phase = phase;
  return in;
}

HairFrame<float> frameOf(const CoatShape& c, const V& root, const V& n, const V& s, float length,
                         const V& xi = {0, 0, 0}) {
  const HairInput<float> in = inputOf(root, n, s, length, xi, 0.0f);
  HairFrame<float> f;
  hairFrame(c, in, f);
  return f;
}

Eigen::Vector3f randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  Eigen::Vector3f v(g(rng), g(rng), g(rng));
  return v.normalized();
}

TEST(HairMath, BarycentricMixIsTheWeightedSum) {
  // sec. 3.2: h = b1 v1 + b2 v2 + b3 v3.
  EXPECT_FLOAT_EQ(barycentricMix(0.2f, 0.3f, 0.5f, 1.0f, 2.0f, 4.0f), 0.2f + 0.6f + 2.0f);
  EXPECT_EQ(barycentricMix(1.0f, 0.0f, 0.0f, 7.0f, 2.0f, 4.0f), 7.0f);
}

TEST(HairMath, WeightlessDirectionBlendsNormalAndSegmentDirection) {
  // sec. 3.4: d = normalize((1 - w) n + w s).
  const V n = v3(0, 0, 1), s = v3(1, 0, 0);
  const Eigen::Vector3f half = E(weightlessDirection(n, s, 0.5f));
  EXPECT_NEAR(half.x(), std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(half.y(), 0.0f, 1e-7f);
  EXPECT_NEAR(half.z(), std::sqrt(0.5f), 1e-6f);
  EXPECT_TRUE(E(weightlessDirection(n, s, 0.0f)).isApprox(E(n), 1e-7f));
  EXPECT_TRUE(E(weightlessDirection(n, s, 1.0f)).isApprox(E(s), 1e-7f));
  // The unnormalised interpolated s is normalised first: |s| does not change the blend.
  EXPECT_TRUE(E(weightlessDirection(n, v3(0.25f, 0, 0), 0.5f)).isApprox(half, 1e-6f));
  // No segment direction (s = 0): d = n exactly.
  const V d0 = weightlessDirection(n, v3(0, 0, 0), 0.7f);
  EXPECT_EQ(d0.x, 0.0f);
  EXPECT_EQ(d0.y, 0.0f);
  EXPECT_EQ(d0.z, 1.0f);
  // A blend that vanishes (s = -n, w = 0.5) falls back to n, never NaN.
  const V opposite = weightlessDirection(n, v3(0, 0, -1), 0.5f);
  EXPECT_EQ(E(opposite), E(n));
}

TEST(HairMath, GravityWithZUpIsThePapersZSubtraction) {
  // sec. 3.5: "f cos(theta) is subtracted from the Z coordinate of the hair's weightless hair
  // direction vector", renormalised. Hand case: d~ = (1, 0, 1)/sqrt 2, n = Z, f = 0.8:
  // cos(theta) = 1/sqrt 2, d' = (0.70711, 0, 0.70711 - 0.56569) -> e = (0.98058, 0, 0.19612).
  const CoatShape c = shapeFor(HairStyle::Line, 0.2f);
  ASSERT_FLOAT_EQ(c.floppiness, 0.8f);
  const V d = v3(std::sqrt(0.5f), 0, std::sqrt(0.5f));
  const Eigen::Vector3f e = E(droopDirection(c, d, v3(0, 0, 1), c.floppiness));
  EXPECT_NEAR(e.x(), 0.980581f, 1e-5f);
  EXPECT_NEAR(e.y(), 0.0f, 1e-7f);
  EXPECT_NEAR(e.z(), 0.196116f, 1e-5f);
  // Random directions and normals: the general-U formula with U = Z is exactly the paper's.
  std::mt19937 rng(7);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3f dt = randomUnit(rng), n = randomUnit(rng);
    const float cosTheta = dt.dot(n);
    const Eigen::Vector3f paper =
        Eigen::Vector3f(dt.x(), dt.y(), dt.z() - 0.8f * cosTheta).normalized();
    EXPECT_TRUE(E(droopDirection(c, fromE(dt), fromE(n), c.floppiness)).isApprox(paper, 1e-5f))
        << k;
  }
}

TEST(HairMath, StiffHairsEndNearTheWeightlessEndAndFloppyOnesOnTheSkinPlane) {
  std::mt19937 rng(3);
  const V n = v3(0, 0, 1);                                   // a horizontal skin patch facing up
  const CoatShape stiff = shapeFor(HairStyle::Line, 1.0f);   // f = 0.02
  const CoatShape floppy = shapeFor(HairStyle::Line, 0.0f);  // f = 1
  ASSERT_FLOAT_EQ(stiff.floppiness, 0.02f);
  ASSERT_FLOAT_EQ(floppy.floppiness, 1.0f);
  for (int k = 0; k < 500; ++k) {
    Eigen::Vector3f d = randomUnit(rng);
    d.z() = std::abs(d.z()) + 0.05f;  // pointing away from the skin
    d.normalize();
    // f = 0.02: |E - W| = L |e - d| <= about 0.02 L.
    EXPECT_LT((E(droopDirection(stiff, fromE(d), n, stiff.floppiness)) - d).norm(), 0.021f) << k;
    // f = 1 on a horizontal patch: d' = d - (d.n) n lies in the skin plane.
    EXPECT_NEAR(E(droopDirection(floppy, fromE(d), n, floppy.floppiness)).z(), 0.0f, 1e-6f) << k;
  }
}

TEST(HairMath, TurningTheBodyOverFlipsTheDroop) {
  // The same hair on a patch facing up and on the patch turned upside down (rotated pi about X):
  // both droop toward world -Z, i.e. toward the skin on top and away from it underneath.
  const CoatShape c = shapeFor(HairStyle::Line, 0.2f, 0.5f);
  const V s = v3(1, 0, 0);  // segment direction along the body, unchanged by the turn
  const HairFrame<float> up = frameOf(c, v3(0, 0, 0), v3(0, 0, 1), s, 1.0f);
  const HairFrame<float> down = frameOf(c, v3(0, 0, 0), v3(0, 0, -1), s, 1.0f);
  const Eigen::Vector3f dropUp = E(up.e) - E(up.dTilde), dropDown = E(down.e) - E(down.dTilde);
  EXPECT_LT(dropUp.z(), -0.1f);
  EXPECT_LT(dropDown.z(), -0.1f);
  EXPECT_LT(dropUp.dot(E(up.normal)), 0.0f);      // toward the skin
  EXPECT_GT(dropDown.dot(E(down.normal)), 0.0f);  // away from the skin
  // Reversing gravity (U = -Z) reverses the droop of the upright patch.
  FurParams p;
  p.coats[0].style = HairStyle::Line;
  p.coats[0].segmentDirectionWeight = 0.5f;
  p.up = Eigen::Vector3f(0, 0, -1);
  const HairFrame<float> reversed = frameOf(makeCoatShape(p, 0), v3(0, 0, 0), v3(0, 0, 1), s, 1.0f);
  EXPECT_GT(E(reversed.e).z() - E(reversed.dTilde).z(), 0.1f);
}

TEST(HairMath, StraightUpFloppyHairUsesTheFallbackTangentNeverNaN) {
  // f = 1, d~ = n = U: d' = 0 exactly; e is the coat's tangent perpendicular to U.
  const CoatShape c = shapeFor(HairStyle::Polyline, 0.0f);
  const HairFrame<float> f = frameOf(c, v3(0, 0, 0), v3(0, 0, 1), v3(0, 0, 0), 0.01f);
  EXPECT_NEAR(E(f.e).norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(E(f.e).z(), 0.0f, 1e-7f);
  Collect out;
  emitPolyline(c, f, HairTwist<float>{}, out);
  for (std::size_t i = 0; i < out.p.size(); ++i) {
    EXPECT_TRUE(out.p[i].allFinite());
    EXPECT_TRUE(out.n[i].allFinite());
    EXPECT_NEAR(out.n[i].norm(), 1.0f, 1e-5f);
  }
}

TEST(HairMath, HairEndRandomizePerturbsTheWeightlessEnd) {
  // sec. 3.5: W' = W + r L xi, d~ = normalize(W' - h) = normalize(d + r xi).
  const CoatShape c = shapeFor(HairStyle::Line, 0.2f, 0.0f, 0.5f);
  const V d = v3(0, 0, 1), xi = v3(0.4f, 0.0f, 0.0f);
  const Eigen::Vector3f dt = E(perturbedDirection(c, d, xi));
  EXPECT_TRUE(dt.isApprox(Eigen::Vector3f(0.2f, 0, 1).normalized(), 1e-6f));
  const CoatShape none = shapeFor(HairStyle::Line, 0.2f);
  EXPECT_EQ(E(perturbedDirection(none, d, xi)), E(d));
}

TEST(HairMath, LengthScalesGloballyAndInsideTheRegion) {
  FurParams p;
  p.lengthScale = 2.0f;
  p.coats[0].lengthFactor = 0.5f;
  p.lengthRegion.shape = RegionShape::Sphere;
  p.lengthRegion.center = Eigen::Vector3f(1, 0, 0);
  p.lengthRegion.radius = 0.5f;
  p.lengthRegion.scale = 3.0f;
  const CoatShape c = makeCoatShape(p, 0);
  EXPECT_FLOAT_EQ(hairLength(c, 0.01f, v3(0, 0, 0)), 0.01f);        // 0.01 * 2 * 0.5
  EXPECT_FLOAT_EQ(hairLength(c, 0.01f, v3(1.2f, 0, 0)), 0.03f);     // inside: * 3
  EXPECT_FLOAT_EQ(hairLength(c, 0.01f, v3(1.0f, 0.5f, 0)), 0.03f);  // on the surface counts
  p.lengthRegion.shape = RegionShape::Box;
  p.lengthRegion.boxMin = Eigen::Vector3f(-1, -1, 0);
  p.lengthRegion.boxMax = Eigen::Vector3f(1, 1, 1);
  const CoatShape b = makeCoatShape(p, 0);
  EXPECT_FLOAT_EQ(hairLength(b, 0.01f, v3(0.5f, 0.5f, 0.5f)), 0.03f);
  EXPECT_FLOAT_EQ(hairLength(b, 0.01f, v3(0.5f, 0.5f, -0.1f)), 0.01f);
}

TEST(HairMath, LineIsRootToEndWithSkinNormals) {
  // sec. 3.6.
  const CoatShape c = shapeFor(HairStyle::Line, 0.2f, 0.5f);
  const HairFrame<float> f = frameOf(c, v3(1, 2, 3), v3(0, 0, 2), v3(1, 0, 0), 0.02f);
  Collect out;
  emitLine(f, out);
  ASSERT_EQ(out.p.size(), 2u);
  EXPECT_EQ(out.p[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_NEAR((out.p[1] - out.p[0]).norm(), 0.02f, 1e-6f);  // length L (coordinates ~3: ulp 2.4e-7)
  EXPECT_TRUE((out.p[1] - out.p[0]).normalized().isApprox(E(f.e), 1e-5f));
  EXPECT_EQ(out.n[0], Eigen::Vector3f(0, 0, 1));  // the (normalised) skin normal
  EXPECT_EQ(out.n[1], Eigen::Vector3f(0, 0, 1));
}

TEST(HairMath, PolylineFollowsTheQuadraticTemplate) {
  // sec. 3.7 with the lead's template: P(t) = R + t(1 - t)(W - R) + t^2 (E - R), t = i/7.
  const CoatShape c = shapeFor(HairStyle::Polyline, 0.2f);
  HairFrame<float> f{};
  f.root = v3(0, 0, 0);
  f.normal = v3(0, 0, 1);
  f.dTilde = v3(0, 0, 1);
  f.e = v3(1, 0, 0);
  f.length = 1.0f;
  f.planeNormal = hairPlaneNormal(f.dTilde, f.e, f.normal);
  Collect out;
  emitPolyline(c, f, HairTwist<float>{}, out);
  ASSERT_EQ(out.p.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    const float t = static_cast<float>(i) / 7.0f;
    EXPECT_NEAR(out.p[static_cast<std::size_t>(i)].z(), t * (1 - t), 1e-6f) << i;
    EXPECT_NEAR(out.p[static_cast<std::size_t>(i)].x(), t * t, 1e-6f) << i;
  }
  EXPECT_EQ(out.p[0], Eigen::Vector3f(0, 0, 0));  // starts at R
  EXPECT_EQ(out.p[7], Eigen::Vector3f(1, 0, 0));  // ends exactly at E
  // First segment heads toward W: direction (1/49, 6/49) -> within atan(1/6) of d~.
  EXPECT_GT((out.p[1] - out.p[0]).normalized().dot(Eigen::Vector3f(0, 0, 1)), std::cos(0.17f));
}

TEST(HairMath, PolylineNormalsArePerpendicularInPlaneAndOnTheSkinSide) {
  std::mt19937 rng(11);
  const CoatShape c = shapeFor(HairStyle::Polyline, 0.2f, 0.3f, 0.3f);
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3f n = randomUnit(rng);
    const HairFrame<float> f = frameOf(c, v3(0, 0, 0), fromE(n), fromE(randomUnit(rng)), 0.01f,
                                       fromE(0.9f * randomUnit(rng)));
    Collect out;
    emitPolyline(c, f, HairTwist<float>{}, out);
    const Eigen::Vector3f B = E(f.planeNormal);
    EXPECT_NEAR(B.norm(), 1.0f, 1e-5f);
    for (int i = 0; i < 8; ++i) {
      const int s = i == 0 ? 1 : i;  // point 0 uses the first segment
      const Eigen::Vector3f seg =
          out.p[static_cast<std::size_t>(s)] - out.p[static_cast<std::size_t>(s - 1)];
      const Eigen::Vector3f N = out.n[static_cast<std::size_t>(i)];
      EXPECT_NEAR(N.norm(), 1.0f, 2e-5f) << k << " " << i;
      EXPECT_NEAR(N.dot(seg.normalized()), 0.0f, 1e-4f) << k << " " << i;  // perpendicular
      EXPECT_NEAR(N.dot(B), 0.0f, 1e-5f) << k << " " << i;                 // in the hair plane
      // Every point of the hair lies in the plane through R with normal B.
      EXPECT_NEAR(out.p[static_cast<std::size_t>(i)].dot(B), 0.0f, 1e-7f);
    }
    // Oriented to the skin normal's side: the chord's in-plane normal B x e has (B x e) . n >= 0.
    EXPECT_GE(B.cross(E(f.e)).dot(n), -1e-6f);
  }
}

TEST(HairMath, NormalTwistStaysPerpendicularToItsSegment) {
  // sec. 3.7: "each shading normal is rotated through a random angle, with the line segment as
  // axis".
  const CoatShape plain = shapeFor(HairStyle::Polyline, 0.2f, 0.3f);
  FurParams p;
  p.coats[0].style = HairStyle::Polyline;
  p.coats[0].segmentDirectionWeight = 0.3f;
  p.coats[0].normalRandomize = 0.5f;
  const CoatShape twisted = makeCoatShape(p, 0);
  ASSERT_TRUE(twisted.twist);
  const HairFrame<float> f = frameOf(plain, v3(0, 0, 0), v3(0, 0.3f, 1), v3(1, 0, 0), 0.01f);
  HairTwist<float> tw{};
  for (int i = 0; i < 8; ++i) {
    const float angle = 0.5f * 3.14159265f * (static_cast<float>(i) / 3.5f - 1.0f);  // within r pi
    tw.cosAngle[i] = std::cos(angle);
    tw.sinAngle[i] = std::sin(angle);
  }
  Collect a, b;
  emitPolyline(plain, f, tw, a);
  emitPolyline(twisted, f, tw, b);
  for (int i = 0; i < 8; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const int s = i == 0 ? 1 : i;
    const Eigen::Vector3f seg =
        (a.p[static_cast<std::size_t>(s)] - a.p[static_cast<std::size_t>(s - 1)]).normalized();
    EXPECT_EQ(a.p[u], b.p[u]);
    EXPECT_NEAR(b.n[u].norm(), 1.0f, 1e-5f);
    EXPECT_NEAR(b.n[u].dot(seg), 0.0f, 1e-4f);
    EXPECT_NEAR(std::acos(std::clamp(a.n[u].dot(b.n[u]), -1.0f, 1.0f)),
                std::abs(std::atan2(tw.sinAngle[i], tw.cosAngle[i])), 2e-3f);
  }
}

TEST(HairMath, DegenerateHairPlaneFallsBackToThePlaneOfTheSkinNormal) {
  // A hair tangent to the skin (cos(theta) = 0) has no droop: R, W, E are collinear. The fallback
  // plane contains the skin normal: B = d~ x n, oriented so normals face n.
  const CoatShape c = shapeFor(HairStyle::Polyline, 0.2f, 1.0f);
  const HairFrame<float> f = frameOf(c, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), 0.01f);
  EXPECT_TRUE(E(f.e).isApprox(Eigen::Vector3f(1, 0, 0), 1e-6f));
  EXPECT_TRUE(E(f.planeNormal).isApprox(Eigen::Vector3f(0, -1, 0), 1e-6f));
  Collect out;
  emitPolyline(c, f, HairTwist<float>{}, out);
  for (int i = 0; i < 8; ++i) {
    EXPECT_TRUE(out.n[static_cast<std::size_t>(i)].isApprox(Eigen::Vector3f(0, 0, 1), 1e-5f)) << i;
    EXPECT_NEAR(out.p[static_cast<std::size_t>(i)].x(), 0.01f * static_cast<float>(i) / 7.0f,
                1e-8f);
  }
  // Fully degenerate: d~ = n = e (a stiff hair straight up): an axis-based plane, finite.
  const HairFrame<float> up =
      frameOf(shapeFor(HairStyle::Polyline, 0.5f), v3(0, 0, 0), v3(0, 0, 1), v3(0, 0, 0), 0.01f);
  EXPECT_NEAR(E(up.planeNormal).norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(E(up.planeNormal).z(), 0.0f, 1e-7f);
}

// De Casteljau evaluation of the cubic Bezier with control points q0..q3 at t.
Eigen::Vector3f bezier(const Eigen::Vector3f* q, double t) {
  Eigen::Vector3d a[4];
  for (int k = 0; k < 4; ++k) a[k] = q[k].cast<double>();
  for (int r = 3; r > 0; --r)
    for (int k = 0; k < r; ++k) a[k] = (1 - t) * a[k] + t * a[k + 1];
  return a[0].cast<float>();
}

TEST(HairMath, CurveIsTheCubicBezierFromRootAlongTheNormalToTheEnd) {
  // sec. 3.8: P0 = R, P1 = R + (L/3) n_p, P2 = R + (2/3)(E - R), P3 = E.
  std::mt19937 rng(5);
  FurParams p;
  p.coats[0].style = HairStyle::Curve;
  p.coats[0].curvePoints = 9;
  p.coats[0].segmentDirectionWeight = 0.4f;
  const CoatShape c = makeCoatShape(p, 0);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3f n = randomUnit(rng), root = randomUnit(rng);
    const HairFrame<float> f = frameOf(c, fromE(root), fromE(n), fromE(randomUnit(rng)), 0.02f);
    Collect out;
    emitCurve(c, f, out);
    ASSERT_EQ(out.p.size(), 9u);
    const Eigen::Vector3f B = E(f.planeNormal);
    Eigen::Vector3f np = (n - B * n.dot(B)).normalized();
    const Eigen::Vector3f end = root + 0.02f * E(f.e);
    const Eigen::Vector3f q[4] = {root, root + (0.02f / 3) * np, root + (2.0f / 3) * (end - root),
                                  end};
    for (int i = 0; i < 9; ++i) {
      EXPECT_LT((out.p[static_cast<std::size_t>(i)] - bezier(q, i / 8.0)).norm(), 1e-6f)
          << k << " " << i;
      EXPECT_TRUE(out.n[static_cast<std::size_t>(i)].isApprox(n, 1e-6f)) << "the skin normal";
    }
    EXPECT_EQ(out.p[0], root);
    EXPECT_EQ(out.p[8], (root + E(f.e) * 0.02f).eval());
  }
}

TEST(HairMath, HelixKeepsTheEndsAndWindsAtTheGivenRadius) {
  FurParams p;
  p.coats[0].style = HairStyle::Curve;
  p.coats[0].curvePoints = 33;
  p.coats[0].curlRadius = 0.1f;
  p.coats[0].curlTurns = 3.0f;
  const CoatShape curly = makeCoatShape(p, 0);
  p.coats[0].curlRadius = 0.0f;
  const CoatShape plain = makeCoatShape(p, 0);
  const HairInput<float> in =
      inputOf(v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), 0.05f, v3(0, 0, 0), 0.3f);
  HairFrame<float> f;
  hairFrame(curly, in, f);
  Collect a, b;
  emitCurve(plain, f, a);
  emitCurve(curly, f, b);
  EXPECT_EQ(a.p.front(), b.p.front());
  EXPECT_EQ(a.p.back(), b.p.back());
  float largest = 0.0f;
  for (int k = 1; k < 32; ++k) {
    const double t = k / 32.0;
    const Eigen::Vector3f off = b.p[static_cast<std::size_t>(k)] - a.p[static_cast<std::size_t>(k)];
    EXPECT_NEAR(off.norm(), 0.1 * 0.05 * std::sin(M_PI * t), 1e-6) << k;
    const Eigen::Vector3f tangent =
        (a.p[static_cast<std::size_t>(k + 1)] - a.p[static_cast<std::size_t>(k - 1)]).normalized();
    EXPECT_LT(std::abs(off.normalized().dot(tangent)), 0.05f) << "around the curve, k " << k;
    largest = std::max(largest, std::abs(off.dot(E(f.planeNormal))));
  }
  EXPECT_GT(largest, 0.004f) << "a genuine 3D curve leaves the hair plane";
}

TEST(HairMath, SinCosTurnsMatchesTheLibrary) {
  for (int k = 0; k < 4096; ++k) {
    const float u = static_cast<float>(k) / 4096.0f;
    float s = 0, c = 0;
    sinCosTurns(u, s, c);
    EXPECT_NEAR(s, std::sin(2 * M_PI * u), 5e-7) << u;
    EXPECT_NEAR(c, std::cos(2 * M_PI * u), 5e-7) << u;
  }
}

TEST(HairMath, TubeRingsSurroundTheCurveWithOutwardNormals) {
  FurParams p;
  p.coats[0].style = HairStyle::Tube;
  p.coats[0].curvePoints = 6;
  p.coats[0].tubeSides = 5;
  p.coats[0].width = {2.0f, 0.1f};
  const CoatShape c = makeCoatShape(p, 0);
  const HairInput<float> in =
      inputOf(v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), 0.05f, v3(0, 0, 0), 0.0f);
  HairFrame<float> f;
  hairFrame(c, in, f);
  Collect curve, tube;
  FurParams pc = p;
  pc.coats[0].style = HairStyle::Curve;
  emitCurve(makeCoatShape(pc, 0), f, curve);
  emitTube(c, f, tube);
  ASSERT_EQ(tube.p.size(), 30u);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3f center = curve.p[static_cast<std::size_t>(k)];
    const Eigen::Vector3f tangent = curve.p[static_cast<std::size_t>(std::min(k + 1, 5))] -
                                    curve.p[static_cast<std::size_t>(std::max(k - 1, 0))];
    const float radius = 0.001f * (1.0f - 0.95f * static_cast<float>(k) / 5.0f);
    for (int j = 0; j < 5; ++j) {
      const auto q = static_cast<std::size_t>(k * 5 + j);
      EXPECT_NEAR((tube.p[q] - center).norm(), radius, 1e-7f);
      EXPECT_NEAR(tube.n[q].norm(), 1.0f, 1e-6f);
      EXPECT_NEAR(tube.n[q].dot(tangent.normalized()), 0.0f, 1e-5f);
      EXPECT_TRUE(((tube.p[q] - center) / radius).isApprox(tube.n[q], 1e-3f));
    }
  }
  // The shared index pattern winds counter-clockwise seen from outside.
  const std::vector<std::int32_t> tri = tubeTriangles(6, 5);
  ASSERT_EQ(tri.size(), static_cast<std::size_t>(5 * 5 * 2 * 3));
  for (std::size_t t = 0; t < tri.size(); t += 3) {
    const Eigen::Vector3f a = tube.p[static_cast<std::size_t>(tri[t])],
                          b = tube.p[static_cast<std::size_t>(tri[t + 1])],
                          d = tube.p[static_cast<std::size_t>(tri[t + 2])];
    const Eigen::Vector3f outward = tube.n[static_cast<std::size_t>(tri[t])] +
                                    tube.n[static_cast<std::size_t>(tri[t + 1])] +
                                    tube.n[static_cast<std::size_t>(tri[t + 2])];
    EXPECT_GT((b - a).cross(d - a).dot(outward), 0.0f) << "triangle " << t / 3;
  }
}

}  // namespace
}  // namespace pelage::fur
