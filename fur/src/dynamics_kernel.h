// Dynamic hair ends inside the per-frame kernel (fur dynamics, dynamics.h): after the paper's
// quasi-static frame of a block of hairs (sec. 3.2 to 3.5), each hair's ending point follows its
// quasi-static position through a damped spring, and the style is then built from the resulting
// ending direction exactly as before (sec. 3.6 to 3.8). Written once over the lane type T like
// hair_math.h (plain IEEE +, -, *, /, sqrt and selects), so every kernel build gives the same bits.
// Included by kernel_impl.h and by generate.cpp (the clump centres' dynamic ends, scalar): no
// Eigen, nothing beyond <cstdint>.
#pragma once

#include <cstdint>

#include "pelage/fur/hair_math.h"

namespace pelage::fur::detail {

// Floats of state per hair, stored planar (component q of root r at q * stride + r):
// 0-2 offset u = E - E_qs (m), 3-5 end velocity E' (m/s), 6-8 last quasi-static end E_qs (m).
inline constexpr int kDynamicsStateFloats = 9;

// Hair lengths are binned on a log scale for the spring's step: bin b holds lengths within half a
// bin of L_ref 2^((b + kSpringBinOffset) / kSpringBinsPerOctave) (lengths outside [2^-8, 2^4] L_ref
// fall into the end bins), so the frequency of a bin is within 4.4 % of that of its lengths.
inline constexpr int kSpringBinsPerOctave = 16;
inline constexpr int kSpringBinOffset = -8 * kSpringBinsPerOctave;
inline constexpr int kSpringBins = 12 * kSpringBinsPerOctave + 1;

// One coat's dynamics for one kernel call.
struct CoatDynamicsArgs {
  float* state = nullptr;   // kDynamicsStateFloats x stride (planar), world coordinates
  std::int64_t stride = 0;  // the coat's root count
  // Per length bin, the exact one-step propagator (uu, uv, vu, vv) of the free spring
  // u'' + 2 zeta w u' + w^2 u = 0 over dt at that length's w: (u, w) <- (uu u + uv w, vu u + vv w),
  // w = E' - E_qs' the velocity relative to the target. kSpringBins x 4.
  const float* steps = nullptr;
  // round(kSpringBinsPerOctave log2(m)) for the mantissa m in [1, 2) of a length ratio, indexed by
  // its top 8 bits (m = 1 + (j + 0.5) / 256). 256 entries.
  const std::uint8_t* mantissaBins = nullptr;
  float invReferenceLength = 100.0f;  // 1 / L_ref (1/m)
  float invDt = 0.0f;                 // 1 / dt (1/s)
  // Steps since the reset, capped at 2: 0 = no previous target (start on it, at rest), 1 = its
  // velocity is unknown before this step (start moving with it), 2 = running.
  int history = 2;
  bool update = true;  // advance the state (false: read this frame's state, as stored)
  bool emit = true;    // hairs are drawn from the ends (else the hair plane is not needed)
};

namespace {

// The length bin of a hair of length L (m): round(16 log2(L / L_ref)) - kSpringBinOffset, clamped.
inline int springBin(const CoatDynamicsArgs& d, float length) {
  const float r = length * d.invReferenceLength;
  if (!(r > 0.0f)) return 0;
  std::uint32_t bits;
  __builtin_memcpy(&bits, &r, sizeof bits);
  const int exponent = static_cast<int>((bits >> 23) & 0xffu) - 127;
  const int b =
      kSpringBinsPerOctave * exponent + d.mantissaBins[(bits >> 15) & 0xffu] - kSpringBinOffset;
  return b < 0 ? 0 : (b >= kSpringBins ? kSpringBins - 1 : b);
}

// Flushes magnitudes below 1e-30 to 0: a decaying spring would otherwise reach subnormals.
template <class T>
inline Vec3<T> flushTiny(const Vec3<T>& v) {
  const T tiny(1e-30f), zero(0.0f);
  return {pick(greater(absOf(v.x), tiny), v.x, zero), pick(greater(absOf(v.y), tiny), v.y, zero),
          pick(greater(absOf(v.z), tiny), v.z, zero)};
}

// Replaces the ending direction e of a block of hair frames (lanes = hairs `roots[0..N)`, the first
// `count` real) by the dynamic one, advancing the per-hair state when d.update:
//   E_qs = R + L e (the paper's ending point, sec. 3.5), V = (E_qs - E_qs,prev) / dt,
//   w = E' - V (0 on the first two steps after a reset, when V is 0 or E' unknown),
//   (u, w) <- propagator of the hair's length (u, w), E' = V + w,
//   e = normalize(E_qs - R + u)  (e unchanged where that vanishes),
// then recomputes the hair plane (sec. 3.7). The target moves linearly within a step, so the spring
// sees its velocity change at each frame and evolves freely in between (exact for any dt).
template <class T>
inline void dynamicEnds(const CoatShape& c, const CoatDynamicsArgs& d, const std::int32_t* roots,
                        int count, HairFrame<T>& f) {
  constexpr int N = static_cast<int>(sizeof(T) / sizeof(float));
  static_assert(sizeof(T) == N * sizeof(float), "lane types are packed floats");
  float rows[kDynamicsStateFloats][N];
  const bool contiguous = roots[N - 1] - roots[0] == N - 1 && count == N;
  for (int q = 0; q < kDynamicsStateFloats; ++q) {
    const float* src = d.state + q * d.stride;
    if (contiguous)
      __builtin_memcpy(rows[q], src + roots[0], sizeof(rows[q]));
    else
      for (int l = 0; l < N; ++l) rows[q][l] = src[roots[l]];
  }
  T s[kDynamicsStateFloats];
  for (int q = 0; q < kDynamicsStateFloats; ++q) __builtin_memcpy(&s[q], rows[q], sizeof(rows[q]));
  Vec3<T> u{s[0], s[1], s[2]};
  const Vec3<T> target = f.root + f.e * f.length;
  if (d.update) {
    // Each lane's propagator from its length bin.
    float lengths[N], m[4][N];
    __builtin_memcpy(lengths, &f.length, sizeof lengths);
    for (int l = 0; l < N; ++l) {
      const float* step = d.steps + 4 * springBin(d, lengths[l]);
      for (int k = 0; k < 4; ++k) m[k][l] = step[k];
    }
    T uu, uv, vu, vv;
    __builtin_memcpy(&uu, m[0], sizeof m[0]);
    __builtin_memcpy(&uv, m[1], sizeof m[1]);
    __builtin_memcpy(&vu, m[2], sizeof m[2]);
    __builtin_memcpy(&vv, m[3], sizeof m[3]);
    const Vec3<T> previous{s[6], s[7], s[8]};
    const Vec3<T> zero{T(0.0f), T(0.0f), T(0.0f)};
    const Vec3<T> v = d.history == 0 ? zero : (target - previous) * T(d.invDt);
    const Vec3<T> w = d.history < 2 ? zero : Vec3<T>{s[3], s[4], s[5]} - v;
    const Vec3<T> u1 = flushTiny(u * uu + w * uv);
    const Vec3<T> w1 = flushTiny(u * vu + w * vv);
    const Vec3<T> velocity = v + w1;
    u = u1;
    const T out[kDynamicsStateFloats] = {u.x,        u.y,      u.z,      velocity.x, velocity.y,
                                         velocity.z, target.x, target.y, target.z};
    for (int q = 0; q < kDynamicsStateFloats; ++q) {
      __builtin_memcpy(rows[q], &out[q], sizeof(rows[q]));
      float* dst = d.state + q * d.stride;
      if (contiguous)
        __builtin_memcpy(dst + roots[0], rows[q], sizeof(rows[q]));
      else
        for (int l = 0; l < count; ++l) dst[roots[l]] = rows[q][l];
    }
  }
  f.e = normalizeOr((target - f.root) + u, f.e, 1e-20f);
  if (d.emit && c.style != HairStyle::Line)
    f.planeNormal = hairPlaneNormal(f.dTilde, f.e, f.normal);
}

}  // namespace
}  // namespace pelage::fur::detail
