// Fur dynamics (dynamics.h): the spring step against closed-form solutions, settling time and
// overshoot, and the damped hair ends on hand-made motions of a small furred plate with known
// answers (still body, uniform velocity, constant acceleration, a sudden turn), determinism across
// threads and SIMD paths, and culling.
#include "pelage/fur/dynamics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "support/skins.h"

namespace pelage::fur {
namespace {

constexpr double kPi = 3.14159265358979323846;

// x(t) of u'' + 2 zeta w u' + w^2 u = 0 from (x0, v0), in closed form.
double freeResponse(double f, double zeta, double x0, double v0, double t) {
  const double w = 2 * kPi * f;
  if (zeta < 1.0) {
    const double wd = w * std::sqrt(1 - zeta * zeta);
    return std::exp(-zeta * w * t) *
           (x0 * std::cos(wd * t) + (v0 + zeta * w * x0) / wd * std::sin(wd * t));
  }
  if (zeta == 1.0) return std::exp(-w * t) * (x0 + (v0 + w * x0) * t);
  const double q = w * std::sqrt(zeta * zeta - 1), r1 = -zeta * w + q, r2 = -zeta * w - q;
  const double c1 = (v0 - r2 * x0) / (r1 - r2), c2 = x0 - c1;
  return c1 * std::exp(r1 * t) + c2 * std::exp(r2 * t);
}

TEST(SpringStep, MatchesTheClosedFormSolutions) {
  for (double zeta : {0.0, 0.1, 0.5, 0.999, 1.0, 1.001, 2.0, 8.0})
    for (double t : {0.001, 1.0 / 30.0, 0.25, 1.0}) {
      SCOPED_TRACE(testing::Message() << "zeta " << zeta << " t " << t);
      const double f = 3.0, w = 2 * kPi * f;
      const SpringStep m = springStep(f, zeta, t);
      // Columns: the response from (1, 0) and from (0, 1), and the velocities by differences.
      const double h = 1e-6;
      EXPECT_NEAR(m.uu, freeResponse(f, zeta, 1, 0, t), 1e-9);
      EXPECT_NEAR(m.uv, freeResponse(f, zeta, 0, 1, t), 1e-9);
      EXPECT_NEAR(
          m.vu, (freeResponse(f, zeta, 1, 0, t + h) - freeResponse(f, zeta, 1, 0, t - h)) / (2 * h),
          1e-4 * w * w);
      EXPECT_NEAR(
          m.vv, (freeResponse(f, zeta, 0, 1, t + h) - freeResponse(f, zeta, 0, 1, t - h)) / (2 * h),
          1e-4 * w);
    }
}

TEST(SpringStep, StepsComposeAndTheEnergyNeverGrows) {
  const double f = 5.0, w = 2 * kPi * f;
  for (double zeta : {0.0, 0.3, 1.0, 3.0}) {
    const SpringStep a = springStep(f, zeta, 0.01), b = springStep(f, zeta, 0.03);
    const SpringStep ab = springStep(f, zeta, 0.04);
    EXPECT_NEAR(b.uu * a.uu + b.uv * a.vu, ab.uu, 1e-12);
    EXPECT_NEAR(b.uu * a.uv + b.uv * a.vv, ab.uv, 1e-12);
    EXPECT_NEAR(b.vu * a.uu + b.vv * a.vu, ab.vu, 1e-9);
    EXPECT_NEAR(b.vu * a.uv + b.vv * a.vv, ab.vv, 1e-12);
    // Energy w^2 u^2 + v^2 after a long step from any state: never more than before (exact decay
    // for zeta 0: conserved).
    for (double angle = 0; angle < 2 * kPi; angle += 0.3) {
      const double u = std::cos(angle) / w, v = std::sin(angle);
      const SpringStep m = springStep(f, zeta, 0.7);
      const double u1 = m.uu * u + m.uv * v, v1 = m.vu * u + m.vv * v;
      const double e0 = w * w * u * u + v * v, e1 = w * w * u1 * u1 + v1 * v1;
      if (zeta == 0.0)
        EXPECT_NEAR(e1, e0, 1e-9);
      else
        EXPECT_LT(e1, e0);
    }
  }
}

TEST(SettlingTime, BoundsTheFreeResponseAndIsTight) {
  for (double f : {1.0, 4.0})
    for (double zeta : {0.05, 0.25, 0.7, 1.0, 1.5, 4.0}) {
      SCOPED_TRACE(testing::Message() << "f " << f << " zeta " << zeta);
      const double tol = 0.02;
      const double ts = settlingTime(f, zeta, tol);
      // The last time |x| exceeds the tolerance, on a fine grid.
      double last = 0.0;
      for (double t = 0.0; t < 3.0 * ts; t += ts / 20000.0)
        if (std::abs(springStep(f, zeta, t).uu) > tol) last = t;
      EXPECT_LE(last, ts);
      if (zeta >= 1.0) {
        EXPECT_NEAR(springStep(f, zeta, ts).uu, tol, 1e-9);  // monotone: exactly there
      } else {
        const double wd = 2 * kPi * f * std::sqrt(1 - zeta * zeta);
        EXPECT_GE(last, ts - kPi / wd - ts / 10000.0);  // the envelope touches once per half period
      }
    }
  EXPECT_TRUE(std::isinf(settlingTime(2.0, 0.0, 0.02)));
}

TEST(OvershootFraction, IsTheFirstTroughOfTheFreeResponse) {
  for (double zeta : {0.05, 0.2, 0.5, 0.9}) {
    double lowest = 1.0;
    for (double t = 0.0; t < 2.0; t += 1e-5) lowest = std::min(lowest, springStep(1.0, zeta, t).uu);
    EXPECT_NEAR(-lowest, overshootFraction(zeta), 1e-6) << zeta;
  }
  EXPECT_EQ(overshootFraction(1.0), 0.0);
  EXPECT_EQ(overshootFraction(3.0), 0.0);
}

TEST(DynamicsParams, OutOfRangeValuesNameTheFieldAndRange) {
  DynamicsParams p;
  EXPECT_NO_THROW(validateDynamicsParams(p, "test"));
  p.coats[1].frequencyHz = 0.0f;
  try {
    validateDynamicsParams(p, "test");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("undercoat dynamics frequency 0 Hz is out of range (0, 100]"),
        std::string::npos)
        << e.what();
  }
  p = {};
  p.coats[0].dampingRatio = -1.0f;
  EXPECT_THROW(validateDynamicsParams(p, "test"), InputError);
  p.coats[0].dampingRatio = std::nanf("");
  EXPECT_THROW(validateDynamicsParams(p, "test"), InputError);
}

// ---- A furred plate moved rigidly ----------------------------------------------------------

// A 10 x 10 cm plate (normal +Z) with 1 cm fur, 2000 hairs, floppiness 0.8, moved rigidly.
struct Plate {
  skin::SkinMesh skin;
  FurParams params;
  FurRoots roots;
  skin::DeformedSkin rest;
  explicit Plate(HairStyle style = HairStyle::Line, double hairs = 2000, float length = 0.01f)
      : skin(test::makeGrid(10, 0.01f, length)) {
    params = test::simpleParams(style, hairs);
    roots = growRoots(skin, params);
    skin::restSkin(skin, rest);
  }
  // The plate turned about its centre and moved: x -> R (x - c) + c + t.
  skin::DeformedSkin moved(const Eigen::Matrix3f& rotation, const Eigen::Vector3f& t) const {
    skin::DeformedSkin d = rest;
    const Eigen::Vector3f c(0.05f, 0.05f, 0.0f);
    for (std::size_t v = 0; v < d.positions.size(); ++v) {
      d.positions[v] = rotation * (rest.positions[v] - c) + c + t;
      d.normals[v] = rotation * rest.normals[v];
      d.directions[v] = rotation * rest.directions[v];
    }
    return d;
  }
};

Eigen::Matrix3f turnX(double degrees) {
  return Eigen::AngleAxisf(static_cast<float>(degrees * kPi / 180.0), Eigen::Vector3f::UnitX())
      .toRotationMatrix();
}

// Largest |u| over the overcoat's hairs (m).
double largestOffset(const FurDynamicsState& s) {
  double m = 0.0;
  for (std::int64_t r = 0; r < s.rootCounts[0]; ++r) {
    float u[3];
    dynamicOffset(s, 0, r, u);
    m = std::max(m, std::sqrt(double(u[0]) * u[0] + double(u[1]) * u[1] + double(u[2]) * u[2]));
  }
  return m;
}

TEST(FurDynamics, StartsOnAndAStillBodyConvergesToTheQuasiStaticHairs) {
  for (HairStyle style :
       {HairStyle::Line, HairStyle::Polyline, HairStyle::Curve, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    const Plate plate(style, 1000);
    DynamicsParams dyn;
    FurDynamicsState state;
    resetFurDynamics(plate.roots, state);
    FurWorkspace ws;
    FurFrame frame;
    const double dt = 1.0 / 60.0;
    // First steps: exactly on the quasi-static hairs (no offset yet).
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, plate.rest, dt, {}, state, ws,
                       frame);
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, plate.rest, dt, {}, state, ws,
                       frame);
    const FurFrame still = test::furFrame(plate.skin, plate.roots, plate.params, plate.rest);
    ASSERT_EQ(frame.coats[0].drawn, still.coats[0].drawn);
    const std::size_t floats =
        static_cast<std::size_t>(frame.coats[0].drawn * frame.coats[0].layout.pointsPerHair() * 3);
    double worst = 0.0;
    for (std::size_t i = 0; i < floats; ++i)
      worst = std::max(worst, double(std::abs(frame.coats[0].positions.data()[i] -
                                              still.coats[0].positions.data()[i])));
    EXPECT_LT(worst, 2e-8);  // only the end direction's rounding through E_qs - R
    // Then the plate turns 60 degrees in one frame and stays: the hairs swing, then converge to
    // the quasi-static hairs of the turned plate.
    const skin::DeformedSkin turned = plate.moved(turnX(60), Eigen::Vector3f::Zero());
    const FurFrame target = test::furFrame(plate.skin, plate.roots, plate.params, turned);
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, turned, dt, {}, state, ws,
                       frame);
    worst = 0.0;
    for (std::size_t i = 0; i < floats; ++i)
      worst = std::max(worst, double(std::abs(frame.coats[0].positions.data()[i] -
                                              target.coats[0].positions.data()[i])));
    EXPECT_GT(worst, 1e-3) << "right after the turn the hairs lag";
    for (int i = 0; i < 600; ++i)  // 10 s, about 40 settling times
      generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, turned, dt, {}, state, ws,
                         frame);
    worst = 0.0;
    for (std::size_t i = 0; i < floats; ++i)
      worst = std::max(worst, double(std::abs(frame.coats[0].positions.data()[i] -
                                              target.coats[0].positions.data()[i])));
    EXPECT_LT(worst, 1e-6);
  }
}

TEST(FurDynamics, UniformMotionLeavesTheHairsOnTheQuasiStaticShape) {
  const Plate plate;
  DynamicsParams dyn;
  FurDynamicsState state;
  resetFurDynamics(plate.roots, state);
  FurWorkspace ws;
  const double dt = 1.0 / 30.0;
  const Eigen::Vector3f velocity(0.8f, -0.3f, 0.5f);  // m/s
  for (int i = 0; i < 60; ++i) {
    const skin::DeformedSkin d = plate.moved(turnX(30), velocity * static_cast<float>(i * dt));
    stepFurDynamics(plate.skin, plate.roots, plate.params, dyn, d, dt, state, ws);
  }
  // Float rounding of the world positions (about 1e-7 m / frame) is all that is left.
  EXPECT_LT(largestOffset(state), 2e-6);
}

TEST(FurDynamics, HairFrequencyFallsWithTheSquareOfTheLength) {
  CoatDynamics c{8.0f, 0.3f};
  EXPECT_DOUBLE_EQ(hairFrequencyHz(c, kDynamicsReferenceLength), 8.0);
  EXPECT_NEAR(hairFrequencyHz(c, 0.02), 2.0, 1e-6);
  EXPECT_NEAR(hairFrequencyHz(c, 0.005), 32.0, 1e-5);
}

// Under a constant acceleration a, every hair's end settles at u = -a / w^2, w = 2 pi f0 (L_ref /
// L)^2; f0 is chosen so that w is 2 Hz at each length (1 cm: f0 = 2 Hz, 2 cm: 8 Hz, 7 mm: 0.98 Hz;
// the 7 mm hairs' bin length is within 1/32 octave: w^2 within 9 %).
class ConstantAcceleration : public testing::TestWithParam<float> {};
TEST_P(ConstantAcceleration, HoldsTheEndsBackByAOverOmegaSquared) {
  const float length = GetParam();
  const Plate plate(HairStyle::Line, 2000, length);
  DynamicsParams dyn;
  const float ratio = length / kDynamicsReferenceLength;
  dyn.coats[0] = {2.0f * ratio * ratio, 0.7f};
  FurDynamicsState state;
  resetFurDynamics(plate.roots, state);
  FurWorkspace ws;
  const double dt = 1.0 / 240.0, w = 2 * kPi * hairFrequencyHz(dyn.coats[0], length);
  EXPECT_NEAR(w, 2 * kPi * 2.0, 1e-4);
  const double tolerance = length == 0.01f ? 0.02 : 0.1;
  const Eigen::Vector3d a(3.0, 0.0, -2.0);  // m/s^2
  for (int i = 0; i < 480; ++i) {           // 2 s: 12 settling times of zeta 0.7 at 2 Hz
    const double t = i * dt;
    const Eigen::Vector3f shift = (0.5 * a * t * t).cast<float>();
    stepFurDynamics(plate.skin, plate.roots, plate.params, dyn,
                    plate.moved(Eigen::Matrix3f::Identity(), shift), dt, state, ws);
  }
  // Steady state of u'' + 2 zeta w u' + w^2 u = -a: u = -a / w^2, for every hair.
  const Eigen::Vector3d expected = -a / (w * w);
  for (std::int64_t r = 0; r < state.rootCounts[0]; r += 97) {
    float u[3];
    dynamicOffset(state, 0, r, u);
    EXPECT_NEAR(u[0], expected.x(), tolerance * expected.norm());
    EXPECT_NEAR(u[1], expected.y(), tolerance * expected.norm());
    EXPECT_NEAR(u[2], expected.z(), tolerance * expected.norm());
  }
}
INSTANTIATE_TEST_SUITE_P(Lengths, ConstantAcceleration, testing::Values(0.01f, 0.02f, 0.007f));

TEST(FurDynamics, ASuddenTurnLagsThenSettlesWithinThePredictedTime) {
  const Plate plate;
  for (float zeta : {0.15f, 0.5f}) {
    SCOPED_TRACE(zeta);
    DynamicsParams dyn;
    dyn.coats[0] = {3.0f, zeta};
    FurDynamicsState state;
    resetFurDynamics(plate.roots, state);
    FurWorkspace ws;
    FurFrame frame;
    const double dt = 1.0 / 120.0;
    const skin::DeformedSkin before = plate.rest,
                             after = plate.moved(turnX(25), Eigen::Vector3f::Zero());
    for (int i = 0; i < 3; ++i)
      generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, before, dt, {}, state, ws,
                         frame);
    const FurFrame oldStatic = test::furFrame(plate.skin, plate.roots, plate.params, before);
    const FurFrame newStatic = test::furFrame(plate.skin, plate.roots, plate.params, after);
    // The turn happens during one frame; the hairs lag: each ending point moves no more than its
    // root does (the root drags it) plus the part of the quasi-static end's displacement that the
    // spring follows within the step, 1 - uv / dt (u(dt) = -uv V from u = 0, w = -V, V dt = dT).
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, after, dt, {}, state, ws, frame);
    const auto followed = static_cast<float>(1.0 - springStep(3.0, zeta, dt).uv / dt);
    EXPECT_LT(followed, 0.1f);
    int lagging = 0;
    const std::int64_t n = frame.coats[0].drawn;
    for (std::int64_t h = 0; h < n; ++h) {
      const Eigen::Vector3f old = test::point(oldStatic.coats[0], h, 1);
      const float moved = (test::point(frame.coats[0], h, 1) - old).norm();
      const float rootMoved =
          (test::point(newStatic.coats[0], h, 0) - test::point(oldStatic.coats[0], h, 0)).norm();
      const float quasiStatic = (test::point(newStatic.coats[0], h, 1) - old).norm();
      lagging += moved <= rootMoved + (followed + 0.01f) * quasiStatic;
    }
    EXPECT_EQ(lagging, n);
    // From the next frame on the target is still: each component of u is a free response
    // e^(-zeta w t) (x0 cos(wd t) + (v0 + zeta w x0) / wd sin(wd t)), bounded by e^(-zeta w t) A,
    // A^2 = x0^2 + ((v0 + zeta w x0) / wd)^2 summed over components.
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, after, dt, {}, state, ws, frame);
    const double w = 2 * kPi * 3.0, wd = w * std::sqrt(1.0 - double(zeta) * zeta);
    double amplitude = 0.0;
    const std::int64_t roots = state.roots(0);
    for (std::int64_t r = 0; r < roots; ++r) {
      double a2 = 0.0;
      for (int q = 0; q < 3; ++q) {
        const double x0 = planar(state.offset(0), roots, r, q);
        const double v0 = planar(state.velocity(0), roots, r, q);
        a2 += x0 * x0 + std::pow((v0 + zeta * w * x0) / wd, 2);
      }
      amplitude = std::max(amplitude, std::sqrt(a2));
    }
    ASSERT_GT(amplitude, 1e-3);
    const double tol = 0.02;
    const double predicted = std::log(1.0 / tol) / (zeta * w);  // e^(-zeta w t) = tol
    double settled = 0.0;
    for (int i = 1; i * dt < 3.0 * predicted; ++i) {
      generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, after, dt, {}, state, ws,
                         frame);
      const double m = largestOffset(state);
      EXPECT_LE(m, amplitude * std::exp(-zeta * w * i * dt) * (1 + 1e-4) + 1e-7) << i;
      if (m > tol * amplitude) settled = i * dt;
    }
    EXPECT_LE(settled, predicted);
    EXPECT_GE(settled, 0.5 * predicted) << "settles suspiciously fast: the damping is wrong";
  }
}

// A plate that turns and accelerates, for the bit-identity checks.
skin::DeformedSkin wobble(const Plate& plate, int i) {
  return plate.moved(turnX(40.0 * std::sin(0.3 * i)),
                     Eigen::Vector3f(0.01f * i * i, 0.0f, 0.02f * std::cos(0.5 * i)));
}

TEST(FurDynamics, BitIdenticalWhateverTheThreadsAndTheSimdPath) {
  const Plate plate(HairStyle::Polyline, 20000);  // several parallel tasks
  auto run = [&](int threads, const std::string& target, FurDynamicsState& state, FurFrame& frame) {
    setThreadCount(threads);
    if (!setKernelTarget(target)) return false;
    DynamicsParams dyn;
    resetFurDynamics(plate.roots, state);
    FurWorkspace ws;
    for (int i = 0; i < 12; ++i)
      generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, wobble(plate, i), 1.0 / 30.0,
                         {}, state, ws, frame);
    return true;
  };
  FurDynamicsState ref;
  FurFrame refFrame;
  const std::vector<std::string> targets = kernelTargets();
  ASSERT_FALSE(targets.empty());
  ASSERT_TRUE(run(1, targets.back(), ref, refFrame));  // the plainest target
  ASSERT_GT(largestOffset(ref), 1e-4);                 // the motion did swing the hairs
  for (int threads : {1, 2, 4})
    for (const std::string& target : targets) {
      FurDynamicsState s;
      FurFrame f;
      ASSERT_TRUE(run(threads, target, s, f));
      SCOPED_TRACE(testing::Message() << threads << " threads, " << target);
      EXPECT_EQ(s.coats[0], ref.coats[0]);
      EXPECT_TRUE(test::sameHairs(f, refFrame));
    }
  setThreadCount(0);
  setKernelTarget("auto");
}

TEST(FurDynamics, CullingDrawsASubsetOfTheSameHairsAndAdvancesEveryHair) {
  const Plate plate(HairStyle::Polyline, 4000);
  DynamicsParams dyn;
  FurDynamicsState whole, culled;
  resetFurDynamics(plate.roots, whole);
  resetFurDynamics(plate.roots, culled);
  FurWorkspace ws1, ws2;
  FurFrame all, some;
  FurView far;
  far.culling = true;
  far.referenceDistance = 1.0f;
  far.viewDistance = 3.0f;
  for (int i = 0; i < 8; ++i) {
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, wobble(plate, i), 1.0 / 30.0, {},
                       whole, ws1, all);
    generateDynamicFur(plate.skin, plate.roots, plate.params, dyn, wobble(plate, i), 1.0 / 30.0,
                       far, culled, ws2, some);
  }
  EXPECT_EQ(culled.coats[0], whole.coats[0]);
  const HairBuffers& a = all.coats[0];
  const HairBuffers& b = some.coats[0];
  ASSERT_GT(b.drawn, 0);
  ASSERT_LT(b.drawn, a.drawn / 2);
  const int P = a.layout.pointsPerHair();
  for (std::int64_t h = 0; h < b.drawn; ++h) {
    const std::int32_t id = b.hairIds[static_cast<std::size_t>(h)];
    ASSERT_EQ(a.hairIds[static_cast<std::size_t>(id)], id);
    EXPECT_EQ(std::memcmp(b.positions.data() + h * P * 3, a.positions.data() + id * P * 3,
                          sizeof(float) * P * 3),
              0);
    EXPECT_EQ(std::memcmp(b.normals.data() + h * P * 3, a.normals.data() + id * P * 3,
                          sizeof(float) * P * 3),
              0);
  }
}

TEST(FurDynamics, StiffSpringsFollowTheTargetMoreClosely) {
  const Plate plate;
  double previous = 1e9;
  for (float f0 : {1.0f, 2.0f, 4.0f, 8.0f, 16.0f}) {
    DynamicsParams dyn;
    dyn.coats[0] = {f0, 0.3f};
    FurDynamicsState state;
    resetFurDynamics(plate.roots, state);
    FurWorkspace ws;
    double worst = 0.0;
    for (int i = 0; i < 60; ++i) {
      stepFurDynamics(plate.skin, plate.roots, plate.params, dyn, wobble(plate, i), 1.0 / 60.0,
                      state, ws);
      worst = std::max(worst, largestOffset(state));
    }
    EXPECT_LT(worst, previous) << f0;
    previous = worst;
  }
}

TEST(FurDynamics, DynamicHairsClumpByTheStrength) {
  // Clumping (fur_params.h Clump) on the dynamic hairs: the damped ends do not depend on the
  // clumps, so each clumped hair's strand point k lies (1 - s_k) of the way it lies, in the same
  // run without clumps, from its centre hair's; centres and hairs in no clump are bit for bit
  // those of that run. Frames: the plate still, turned 60 degrees (the hairs swing), still.
  for (HairStyle style : {HairStyle::Polyline, HairStyle::Tube}) {
    SCOPED_TRACE(styleName(style));
    const Plate plate(style, 2000);
    FurParams p = plate.params;
    p.coats[0].clump = {.density = 1.0f, .strength = 0.7f, .shape = 1.0f, .radiusMm = 15.0f};
    const FurRoots roots = growRoots(plate.skin, p);
    const CoatRoots& cr = roots.coats[0];
    ASSERT_FALSE(cr.clumpCentres.empty());
    FurParams plain = p;
    plain.coats[0].clump.strength = 0.0f;  // off: the same roots, no clumping
    DynamicsParams dyn;
    FurDynamicsState sa, sb;
    resetFurDynamics(roots, sa);
    resetFurDynamics(roots, sb);
    FurWorkspace wa, wb;
    FurFrame a, b;
    const double dt = 1.0 / 60.0;
    const skin::DeformedSkin turned = plate.moved(turnX(60), Eigen::Vector3f::Zero());
    std::int64_t clumped = 0;
    for (const skin::DeformedSkin* d : {&plate.rest, &plate.rest, &turned, &turned, &turned}) {
      generateDynamicFur(plate.skin, roots, plain, dyn, *d, dt, {}, sa, wa, a);
      generateDynamicFur(plate.skin, roots, p, dyn, *d, dt, {}, sb, wb, b);
      const HairBuffers &ha = a.coats[0], &hb = b.coats[0];
      ASSERT_EQ(ha.drawn, hb.drawn);
      const int K = hb.layout.strandPoints, P = hb.layout.pointsPerHair();
      clumped = 0;
      for (std::int64_t h = 0; h < hb.drawn; ++h) {
        const std::int32_t slot = cr.clumpSlot[static_cast<std::size_t>(h)];
        const std::int64_t c = slot < 0 ? h : cr.clumpCentres[static_cast<std::size_t>(slot)];
        if (c == h) {
          for (int i = 0; i < P; ++i) ASSERT_EQ(test::point(hb, h, i), test::point(ha, h, i)) << h;
          continue;
        }
        ++clumped;
        for (int k = 1; k < K; ++k) {
          const float sk = 0.7f * static_cast<float>(k) / static_cast<float>(K - 1);
          const Eigen::Vector3f C = test::strandPoint(ha, c, k);
          const Eigen::Vector3f expected = C + (1.0f - sk) * (test::strandPoint(ha, h, k) - C);
          ASSERT_LE((test::strandPoint(hb, h, k) - expected).norm(), 2e-6f)
              << "hair " << h << " k " << k;
        }
      }
    }
    EXPECT_GT(clumped, 1000);
    EXPECT_GT(largestOffset(sb), 1e-4);  // the last frames swing
  }
}

}  // namespace
}  // namespace pelage::fur
