// The portable lane type of the generic kernel: 8 floats with element-wise IEEE operations in
// plain loops (the compiler vectorises them for the x86-64 baseline, SSE2). Same results as the
// AVX2 lanes and as the scalar reference, bit for bit. Include from one translation unit only.
#pragma once

#include <cmath>

#include "kernel.h"

namespace pelage::fur::detail::generic {
namespace {

struct F {
  float v[kLanes];
  F() = default;
  F(float x) {  // NOLINT(google-explicit-constructor): broadcast, like T(1.0f) for float
    for (int i = 0; i < kLanes; ++i) v[i] = x;
  }
};
struct Mask {
  bool v[kLanes];
};

#define PELAGE_LANEWISE(op)                                     \
  inline F operator op(const F& a, const F& b) {                \
    F r;                                                        \
    for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] op b.v[i]; \
    return r;                                                   \
  }
PELAGE_LANEWISE(+)
PELAGE_LANEWISE(-)
PELAGE_LANEWISE(*)
PELAGE_LANEWISE(/)
#undef PELAGE_LANEWISE

inline F sqrtOf(const F& a) {
  F r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = std::sqrt(a.v[i]);
  return r;
}
inline F floorOf(const F& a) {
  F r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = std::floor(a.v[i]);
  return r;
}
inline F absOf(const F& a) {
  F r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = a.v[i] < 0.0f ? -a.v[i] : a.v[i];
  return r;
}
inline Mask greater(const F& a, const F& b) {
  Mask m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] > b.v[i];
  return m;
}
inline Mask lessEq(const F& a, const F& b) {
  Mask m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] <= b.v[i];
  return m;
}
inline Mask equalTo(const F& a, const F& b) {
  Mask m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] == b.v[i];
  return m;
}
inline Mask andMask(const Mask& a, const Mask& b) {
  Mask m;
  for (int i = 0; i < kLanes; ++i) m.v[i] = a.v[i] && b.v[i];
  return m;
}
inline bool allOf(const Mask& m) {
  bool all = true;
  for (int i = 0; i < kLanes; ++i) all = all && m.v[i];
  return all;
}
inline F pick(const Mask& m, const F& a, const F& b) {
  F r;
  for (int i = 0; i < kLanes; ++i) r.v[i] = m.v[i] ? a.v[i] : b.v[i];
  return r;
}

}  // namespace
}  // namespace pelage::fur::detail::generic
