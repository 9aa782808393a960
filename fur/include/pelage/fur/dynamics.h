// Dynamic fur: an option beyond the paper. Van Gelder & Wilhelms 1997, sec. 3.5, is quasi-static:
// each frame the ending point E_qs = R + L e follows the body's current orientation instantly. Here
// each hair's ending point E instead follows E_qs through a damped spring, so fur lags, overshoots
// and settles when the body accelerates or turns; the hair is then built by its style from the
// resulting ending direction exactly as before (sec. 3.6 to 3.8).
//
// Model (per hair, world coordinates): the paper's E_qs is the equilibrium of the hair under
// gravity for the current pose, so the deviation u = E - E_qs obeys, in the frame moving with E_qs,
//   u'' + 2 zeta w0 u' + w0^2 u = -E_qs''
// (the inertial force of the equilibrium point's acceleration: the root's acceleration, the
// tangential and centripetal acceleration of a turning segment, and the change of droop as the body
// turns relative to gravity). E_qs is sampled once per frame and taken to move linearly in between,
// so the spring runs freely within a step and its relative velocity changes by the jump of E_qs' at
// each frame: an exact step for any frame time, unconditionally stable. The drawn direction is
// e = normalize(E - R), so hairs keep their length. A still body converges to the quasi-static
// hairs. State per hair: u, E' and the last E_qs (9 floats, planar arrays).
//
// A hair is a cantilever: its first bending mode has w ~ 1 / L^2 (Euler-Bernoulli), so short hairs
// (face, hands) are far stiffer than long ones and barely swing. The coat's frequency f0 is given
// for hairs of the reference length L_ref = 1 cm; a hair of length L springs at
// f0 (L_ref / L)^2 (lengths binned at 1/16 octave, frequencies within 4.4 %).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "pelage/fur/culling.h"
#include "pelage/fur/fur_params.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/roots.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/skin_mesh.h"

namespace pelage::fur {

// One coat's spring: natural frequency f0 of a hair of the reference length (stiffness over mass:
// k/m = (2 pi f0)^2) and damping ratio zeta (1 = critically damped; below 1 the hair overshoots).
struct CoatDynamics {
  float frequencyHz = 8.0f;    // f0 at kDynamicsReferenceLength, (0, 100] Hz
  float dampingRatio = 0.25f;  // zeta, [0, 10]
};

// L_ref (m): the hair length the coat frequencies are given for.
inline constexpr float kDynamicsReferenceLength = 0.01f;

// The natural frequency (Hz) of a hair of length `lengthMeters` (> 0): f0 (L_ref / L)^2.
inline double hairFrequencyHz(const CoatDynamics& coat, double lengthMeters) {
  const double r = static_cast<double>(kDynamicsReferenceLength) / lengthMeters;
  return static_cast<double>(coat.frequencyHz) * r * r;
}

struct DynamicsParams {
  std::array<CoatDynamics, kCoatCount> coats{};
};

// Throws InputError naming `source`, the field and the accepted range.
void validateDynamicsParams(const DynamicsParams& params, const std::string& source);

// The exact step of the free spring u'' + 2 zeta w0 u' + w0^2 u = 0 over dt seconds:
// (u, u') <- (uu u + uv u', vu u + vv u'), the matrix exp(A dt), A = [[0, 1], [-w0^2, -2 zeta w0]].
struct SpringStep {
  double uu = 1.0, uv = 0.0, vu = 0.0, vv = 1.0;
};
SpringStep springStep(double frequencyHz, double dampingRatio, double dtSeconds);

// Time (s) after which the free response from a displacement at rest, x(t) = springStep(t).uu,
// stays within `tolerance` (a fraction, (0, 1)) of that displacement. Below critical damping, by
// its envelope e^(-zeta w0 t) / sqrt(1 - zeta^2): t = ln(1 / (tolerance sqrt(1 - zeta^2))) /
// (zeta w0); from critical damping on, x decreases monotonically and t solves x(t) = tolerance.
double settlingTime(double frequencyHz, double dampingRatio, double tolerance);

// Peak overshoot of the free response from a displacement at rest, as a fraction of the
// displacement: exp(-pi zeta / sqrt(1 - zeta^2)) below critical damping, 0 from it on.
double overshootFraction(double dampingRatio);

// Per-hair state between frames (constant model apart: sized to the roots by resetFurDynamics).
struct FurDynamicsState {
  // Per coat, 9 x nRoots floats, planar (component q of root r at q * nRoots + r): 0-2 offset
  // u = E - E_qs (m), 3-5 end velocity E' (m/s), 6-8 the last quasi-static end E_qs (m); world.
  // One block per coat for the kernel; read the fields through the accessors below.
  std::array<std::vector<float>, kCoatCount> coats;
  // Coat c's fields, each (3, n) planar, n = rootCounts[c]: x of every root, then y, then z.
  const float* offset(int c) const { return field(c, 0); }    // u = E - E_qs (m)
  const float* velocity(int c) const { return field(c, 3); }  // E' (m/s)
  const float* lastEnd(int c) const { return field(c, 6); }   // E_qs of the last step (m)
  std::int64_t roots(int c) const { return rootCounts[static_cast<std::size_t>(c)]; }
  std::array<std::int64_t, kCoatCount> rootCounts{0, 0};
  std::int64_t steps = 0;  // frames advanced since the reset
  double dtSeconds = 0.0;  // the last step's frame time
  // Per coat, the spring step of each length bin for the frame time and parameters in `stepKey`
  // (recomputed when they change).
  std::array<std::vector<float>, kCoatCount> springSteps;
  std::array<std::array<double, 3>, kCoatCount> stepKey{};

 private:
  const float* field(int c, int first) const {
    return coats[static_cast<std::size_t>(c)].data() + first * roots(c);
  }
};

// Component q (0 x, 1 y, 2 z) of root r in a (3, n) planar field of FurDynamicsState.
inline float planar(const float* field, std::int64_t n, std::int64_t r, int q) {
  return field[q * n + r];
}

// Sizes the state to `roots` and zeroes it: the next step starts on the quasi-static hairs, at
// rest, and the one after moving with them. Allocates.
void resetFurDynamics(const FurRoots& roots, FurDynamicsState& state);

// Advances every hair's end to the frame of `deformed` (all roots, whatever the culling), dt
// seconds after the previous step (ignored on the first step after a reset). Parallel over hairs,
// bit- identical whatever the thread count. `params` and `dynamics` validated; dt in (0, 10].
void stepFurDynamics(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                     const DynamicsParams& dynamics, const skin::DeformedSkin& deformed,
                     double dtSeconds, FurDynamicsState& state, FurWorkspace& workspace);

// stepFurDynamics, then the frame's hairs as generateFur draws them (culling for `view`), each
// hair's ending direction taken from its dynamic end. One pass over the hairs without culling.
void generateDynamicFur(const skin::SkinMesh& skin, const FurRoots& roots, const FurParams& params,
                        const DynamicsParams& dynamics, const skin::DeformedSkin& deformed,
                        double dtSeconds, const FurView& view, FurDynamicsState& state,
                        FurWorkspace& workspace, FurFrame& frame);

// The dynamic ending point's offset from the quasi-static one, u (m, world), of root `root` of
// coat `coat` after the last step.
inline void dynamicOffset(const FurDynamicsState& state, int coat, std::int64_t root, float u[3]) {
  for (int q = 0; q < 3; ++q) u[q] = planar(state.offset(coat), state.roots(coat), root, q);
}

}  // namespace pelage::fur
