#include "pelage/fur/dynamics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "dynamics_kernel.h"
#include "generate_dynamic.h"
#include "pelage/util/error.h"

namespace pelage::fur {
namespace {

constexpr double kPi = 3.14159265358979323846;

// round(16 log2(1 + (j + 0.5) / 256)) for the top 8 mantissa bits j (dynamics_kernel.h).
const std::uint8_t* mantissaBins() {
  static const auto table = [] {
    std::array<std::uint8_t, 256> t{};
    for (int j = 0; j < 256; ++j)
      t[static_cast<std::size_t>(j)] = static_cast<std::uint8_t>(
          std::lround(detail::kSpringBinsPerOctave * std::log2(1.0 + (j + 0.5) / 256.0)));
    return t;
  }();
  return table.data();
}

// The coat's kernel arguments for one step.
detail::CoatDynamicsArgs coatArgs(const DynamicsParams& dynamics, int coat, double dt,
                                  FurDynamicsState& state, bool update, bool emit) {
  const auto c = static_cast<std::size_t>(coat);
  const CoatDynamics& cd = dynamics.coats[c];
  const std::array<double, 3> key{dt, static_cast<double>(cd.frequencyHz),
                                  static_cast<double>(cd.dampingRatio)};
  std::vector<float>& steps = state.springSteps[c];
  if (steps.size() != 4 * detail::kSpringBins || state.stepKey[c] != key) {
    // Bin b: length L_ref 2^((b + offset) / 16), frequency f0 (L_ref / L)^2.
    steps.resize(4 * detail::kSpringBins);
    for (int b = 0; b < detail::kSpringBins; ++b) {
      const double r = std::exp2(static_cast<double>(b + detail::kSpringBinOffset) /
                                 detail::kSpringBinsPerOctave);
      const SpringStep m = springStep(static_cast<double>(cd.frequencyHz) / (r * r),
                                      static_cast<double>(cd.dampingRatio), dt);
      float* o = steps.data() + 4 * b;
      o[0] = static_cast<float>(m.uu);
      o[1] = static_cast<float>(m.uv);
      o[2] = static_cast<float>(m.vu);
      o[3] = static_cast<float>(m.vv);
    }
    state.stepKey[c] = key;
  }
  detail::CoatDynamicsArgs a;
  a.state = state.coats[c].data();
  a.stride = state.rootCounts[c];
  a.steps = steps.data();
  a.mantissaBins = mantissaBins();
  a.invReferenceLength = 1.0f / kDynamicsReferenceLength;
  a.invDt = static_cast<float>(1.0 / dt);
  a.history = static_cast<int>(std::min<std::int64_t>(state.steps, 2));
  a.update = update;
  a.emit = emit;
  return a;
}

void checkState(const FurRoots& roots, const FurDynamicsState& state, double dt) {
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    PELAGE_CHECK(
        state.rootCounts[ci] == roots.coats[ci].size() &&
            state.coats[ci].size() ==
                static_cast<std::size_t>(detail::kDynamicsStateFloats * roots.coats[ci].size()),
        "dynamics state sized for ", state.rootCounts[ci], " roots, coat ", c, " has ",
        roots.coats[ci].size(), " (call resetFurDynamics)");
  }
  PELAGE_CHECK(dt > 0.0 && dt <= 10.0, "frame time ", dt, " s");
}

}  // namespace

void validateDynamicsParams(const DynamicsParams& params, const std::string& source) {
  for (int c = 0; c < kCoatCount; ++c) {
    const CoatDynamics& cd = params.coats[static_cast<std::size_t>(c)];
    const char* coat = c == 0 ? "overcoat" : "undercoat";
    if (!(cd.frequencyHz > 0.0f && cd.frequencyHz <= 100.0f))
      inputError(source, ": ", coat, " dynamics frequency ", cd.frequencyHz,
                 " Hz is out of range (0, 100]");
    if (!(cd.dampingRatio >= 0.0f && cd.dampingRatio <= 10.0f))
      inputError(source, ": ", coat, " dynamics damping ratio ", cd.dampingRatio,
                 " is out of range [0, 10]");
  }
}

SpringStep springStep(double frequencyHz, double dampingRatio, double dt) {
  // exp(A t) = e^(s t) [C I + S (A - s I)], s = -zeta w0 (half the trace of A), A - s I =
  // [[zeta w0, 1], [-w0^2, -zeta w0]], and with q^2 = w0^2 (zeta^2 - 1) (the eigenvalues are s +-
  // q): C = cosh(q t), S = sinh(q t) / q (q^2 > 0); cos, sin / q (q^2 < 0); 1, t (q = 0).
  const double w0 = 2.0 * kPi * frequencyHz;
  const double zeta = dampingRatio;
  const double s = -zeta * w0;
  const double q2 = w0 * w0 * (zeta * zeta - 1.0);
  double eC = 0.0, eS = 0.0;  // e^(s t) C and e^(s t) S
  if (std::abs(q2) * dt * dt < 1e-12) {
    const double e = std::exp(s * dt);
    eC = e * (1.0 + q2 * dt * dt / 2.0);
    eS = e * dt * (1.0 + q2 * dt * dt / 6.0);
  } else if (q2 > 0.0) {
    const double q = std::sqrt(q2);
    const double e1 = std::exp((s + q) * dt), e2 = std::exp((s - q) * dt);  // no overflow
    eC = 0.5 * (e1 + e2);
    eS = 0.5 * (e1 - e2) / q;
  } else {
    const double q = std::sqrt(-q2);
    const double e = std::exp(s * dt);
    eC = e * std::cos(q * dt);
    eS = e * std::sin(q * dt) / q;
  }
  SpringStep m;
  m.uu = eC + zeta * w0 * eS;
  m.uv = eS;
  m.vu = -w0 * w0 * eS;
  m.vv = eC - zeta * w0 * eS;
  return m;
}

double settlingTime(double frequencyHz, double dampingRatio, double tolerance) {
  PELAGE_CHECK(frequencyHz > 0.0 && dampingRatio >= 0.0 && tolerance > 0.0 && tolerance < 1.0,
               "settlingTime(", frequencyHz, ", ", dampingRatio, ", ", tolerance, ")");
  const double w0 = 2.0 * kPi * frequencyHz;
  const double zeta = dampingRatio;
  if (zeta == 0.0) return std::numeric_limits<double>::infinity();
  if (zeta < 1.0) return std::log(1.0 / (tolerance * std::sqrt(1.0 - zeta * zeta))) / (zeta * w0);
  // Critically or over-damped: x(t) falls monotonically from 1; bisect x(t) = tolerance.
  double lo = 0.0, hi = 1.0 / w0;
  while (springStep(frequencyHz, zeta, hi).uu > tolerance) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (springStep(frequencyHz, zeta, mid).uu > tolerance ? lo : hi) = mid;
  }
  return hi;
}

double overshootFraction(double dampingRatio) {
  if (dampingRatio >= 1.0) return 0.0;
  return std::exp(-kPi * dampingRatio / std::sqrt(1.0 - dampingRatio * dampingRatio));
}

void resetFurDynamics(const FurRoots& roots, FurDynamicsState& state) {
  for (int c = 0; c < kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    state.rootCounts[ci] = roots.coats[ci].size();
    state.coats[ci].assign(
        static_cast<std::size_t>(detail::kDynamicsStateFloats * state.rootCounts[ci]), 0.0f);
  }
  state.steps = 0;
  state.dtSeconds = 0.0;
}

void stepFurDynamics(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                     const DynamicsParams& dynamics, const skin::DeformedSkin& deformed,
                     double dtSeconds, FurDynamicsState& state, FurWorkspace& workspace) {
  const double dt = state.steps == 0 ? 1.0 : dtSeconds;  // unused on the first step
  checkState(roots, state, dt);
  const detail::CoatDynamicsArgs over = coatArgs(dynamics, 0, dt, state, true, false);
  const detail::CoatDynamicsArgs under = coatArgs(dynamics, 1, dt, state, true, false);
  FurFrame unused;
  detail::generateFurWithDynamics(skin, roots, params, deformed, FurView{}, workspace, unused,
                                  {&over, &under}, false);
  ++state.steps;
  state.dtSeconds = dtSeconds;
}

void generateDynamicFur(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                        const DynamicsParams& dynamics, const skin::DeformedSkin& deformed,
                        double dtSeconds, const FurView& view, FurDynamicsState& state,
                        FurWorkspace& workspace, FurFrame& frame) {
  if (cullingFactor(view) > 1.0f || clumps(params)) {
    // Culling draws a subset, and clumps read their centre hairs' dynamic ends before drawing:
    // advance every hair first, then draw from the new state.
    stepFurDynamics(skin, roots, params, dynamics, deformed, dtSeconds, state, workspace);
    const detail::CoatDynamicsArgs over = coatArgs(dynamics, 0, 1.0, state, false, true);
    const detail::CoatDynamicsArgs under = coatArgs(dynamics, 1, 1.0, state, false, true);
    detail::generateFurWithDynamics(skin, roots, params, deformed, view, workspace, frame,
                                    {&over, &under}, true);
    return;
  }
  const double dt = state.steps == 0 ? 1.0 : dtSeconds;
  checkState(roots, state, dt);
  const detail::CoatDynamicsArgs over = coatArgs(dynamics, 0, dt, state, true, true);
  const detail::CoatDynamicsArgs under = coatArgs(dynamics, 1, dt, state, true, true);
  detail::generateFurWithDynamics(skin, roots, params, deformed, view, workspace, frame,
                                  {&over, &under}, true);
  ++state.steps;
  state.dtSeconds = dtSeconds;
}

}  // namespace pelage::fur
