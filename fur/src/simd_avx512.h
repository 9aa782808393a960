// The AVX-512 lane type: 16 floats in a __m512 (32 registers, half the instructions of AVX2 for the
// per-hair maths). Only IEEE add, sub, mul, div, sqrt, compares, blends and floor: results equal
// the other paths bit for bit. Include only from kernel_avx512.cpp.
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "kernel.h"

namespace pelage::fur::detail::avx512 {
namespace {

struct F {
  __m512 v;
  F() = default;
  F(float x) : v(_mm512_set1_ps(x)) {}  // NOLINT(google-explicit-constructor): broadcast
  explicit F(__m512 x) : v(x) {}
};
struct Mask {
  __mmask16 m;
};

inline F operator+(F a, F b) {
  return F(_mm512_add_ps(a.v, b.v));
}
inline F operator-(F a, F b) {
  return F(_mm512_sub_ps(a.v, b.v));
}
inline F operator*(F a, F b) {
  return F(_mm512_mul_ps(a.v, b.v));
}
inline F operator/(F a, F b) {
  return F(_mm512_div_ps(a.v, b.v));
}
inline F sqrtOf(F a) {
  return F(_mm512_sqrt_ps(a.v));
}
inline F floorOf(F a) {
  return F(_mm512_roundscale_ps(a.v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}
inline F absOf(F a) {
  return F(_mm512_abs_ps(a.v));
}
inline Mask greater(F a, F b) {
  return Mask{_mm512_cmp_ps_mask(a.v, b.v, _CMP_GT_OQ)};
}
inline Mask lessEq(F a, F b) {
  return Mask{_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)};
}
inline Mask equalTo(F a, F b) {
  return Mask{_mm512_cmp_ps_mask(a.v, b.v, _CMP_EQ_OQ)};
}
inline Mask andMask(Mask a, Mask b) {
  return Mask{static_cast<__mmask16>(a.m & b.m)};
}
inline F pick(Mask m, F a, F b) {
  return F(_mm512_mask_blend_ps(m.m, b.v, a.v));
}
inline bool allOf(Mask m) {
  return m.m == 0xFFFF;
}

inline __m256 half(__m512 v, int h) {
  return h == 0 ? _mm512_castps512_ps256(v) : _mm512_extractf32x8_ps(v, 1);
}

// 16 x 16 transpose: out[e] lane r = rows[r] lane e.
inline void transpose16(const __m512* rows, __m512* out) {
  __m512 t[16], u[16];
  for (int k = 0; k < 8; ++k) {
    t[2 * k] = _mm512_unpacklo_ps(rows[2 * k], rows[2 * k + 1]);
    t[2 * k + 1] = _mm512_unpackhi_ps(rows[2 * k], rows[2 * k + 1]);
  }
  // u[4 g + c], 128-bit lane j: column 4 j + c of rows 4 g .. 4 g + 3.
  for (int g = 0; g < 4; ++g) {
    u[4 * g] = _mm512_shuffle_ps(t[4 * g], t[4 * g + 2], 0x44);
    u[4 * g + 1] = _mm512_shuffle_ps(t[4 * g], t[4 * g + 2], 0xEE);
    u[4 * g + 2] = _mm512_shuffle_ps(t[4 * g + 1], t[4 * g + 3], 0x44);
    u[4 * g + 3] = _mm512_shuffle_ps(t[4 * g + 1], t[4 * g + 3], 0xEE);
  }
  // A 4 x 4 transpose of 128-bit lanes for each c.
  for (int c = 0; c < 4; ++c) {
    const __m512 v0 = _mm512_shuffle_f32x4(u[c], u[4 + c], 0x44);
    const __m512 v1 = _mm512_shuffle_f32x4(u[c], u[4 + c], 0xEE);
    const __m512 v2 = _mm512_shuffle_f32x4(u[8 + c], u[12 + c], 0x44);
    const __m512 v3 = _mm512_shuffle_f32x4(u[8 + c], u[12 + c], 0xEE);
    out[c] = _mm512_shuffle_f32x4(v0, v2, 0x88);
    out[4 + c] = _mm512_shuffle_f32x4(v0, v2, 0xDD);
    out[8 + c] = _mm512_shuffle_f32x4(v1, v3, 0x88);
    out[12 + c] = _mm512_shuffle_f32x4(v1, v3, 0xDD);
  }
}

// Gathers 16 hairs (sec. 3.2): per hair, (b1 v1 + b2 v2) + b3 v3 (as barycentricMix) of the 12
// floats of its triangle's three packed vertex records in one zmm (lanes 0-11: position, length,
// normal, 0, direction, 0), the root's jitter in lanes 12-15; one 16 x 16 transpose turns the rows
// into lanes.
template <class Input>
inline void gather16(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                     Input& in) {
  constexpr __mmask16 kRecord = 0x0FFF;
  __m512 rows[16], cols[16];
  for (int l = 0; l < 16; ++l) {
    const std::int32_t r = roots[l];
    const float* v[3];
    triangleRecords(a, tris[l], v);
    const float* b = a.barycentric + 4 * static_cast<std::int64_t>(a.tableIndex[r]);
    const __m512 m = _mm512_add_ps(
        _mm512_add_ps(_mm512_mul_ps(_mm512_set1_ps(b[0]), _mm512_maskz_loadu_ps(kRecord, v[0])),
                      _mm512_mul_ps(_mm512_set1_ps(b[1]), _mm512_maskz_loadu_ps(kRecord, v[1]))),
        _mm512_mul_ps(_mm512_set1_ps(b[2]), _mm512_maskz_loadu_ps(kRecord, v[2])));
    rows[l] = _mm512_insertf32x4(m, _mm_loadu_ps(a.jitter + 4 * static_cast<std::int64_t>(r)), 3);
  }
  transpose16(rows, cols);
  in.root = {F(cols[0]), F(cols[1]), F(cols[2])};
  in.length = F(cols[3]);
  in.normalSum = {F(cols[4]), F(cols[5]), F(cols[6])};
  in.directionSum = {F(cols[8]), F(cols[9]), F(cols[10])};
  in.xi = {F(cols[12]), F(cols[13]), F(cols[14])};
  in.phase = F(cols[15]);
}

}  // namespace
}  // namespace pelage::fur::detail::avx512
