// The AVX2 lane type (8 floats in a __m256) and the 8-lane gathers, transposes and stores shared by
// the AVX2 and AVX-512 kernels. Only IEEE add, sub, mul, div, sqrt, compares, blends and floor (no
// FMA, no rsqrt/rcp approximations), so results equal the generic lanes and the scalar reference
// bit for bit. Include only from kernel_avx2.cpp / kernel_avx512.cpp (compiled for those ISAs).
#pragma once

#include <immintrin.h>

#include <cstdint>

#include "kernel.h"
#include "pelage/fur/hair_math.h"

namespace pelage::fur::detail::avx2 {
namespace {

struct F {
  __m256 v;
  F() = default;
  F(float x) : v(_mm256_set1_ps(x)) {}  // NOLINT(google-explicit-constructor): broadcast
  explicit F(__m256 x) : v(x) {}
};
struct Mask {
  __m256 v;
};

inline F operator+(F a, F b) {
  return F(_mm256_add_ps(a.v, b.v));
}
inline F operator-(F a, F b) {
  return F(_mm256_sub_ps(a.v, b.v));
}
inline F operator*(F a, F b) {
  return F(_mm256_mul_ps(a.v, b.v));
}
inline F operator/(F a, F b) {
  return F(_mm256_div_ps(a.v, b.v));
}
inline F sqrtOf(F a) {
  return F(_mm256_sqrt_ps(a.v));
}
inline F floorOf(F a) {
  return F(_mm256_floor_ps(a.v));
}
inline F absOf(F a) {
  return F(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v));
}
inline Mask greater(F a, F b) {
  return Mask{_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)};
}
inline Mask lessEq(F a, F b) {
  return Mask{_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)};
}
inline Mask equalTo(F a, F b) {
  return Mask{_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)};
}
inline Mask andMask(Mask a, Mask b) {
  return Mask{_mm256_and_ps(a.v, b.v)};
}
inline F pick(Mask m, F a, F b) {
  return F(_mm256_blendv_ps(b.v, a.v, m.v));
}
inline bool allOf(Mask m) {
  return _mm256_movemask_ps(m.v) == 0xFF;
}

// Two blocks of 8 lanes side by side (16 hairs): each operation is two independent instructions, so
// the long sqrt/div chains of the per-hair frame (sec. 3.4, 3.5) of one block hide behind the
// other.
struct F2 {
  __m256 v[2];
  F2() = default;
  F2(float x) : v{_mm256_set1_ps(x), _mm256_set1_ps(x)} {}  // NOLINT(google-explicit-constructor)
  F2(__m256 lo, __m256 hi) : v{lo, hi} {}
};
struct Mask2 {
  __m256 v[2];
};
#define PELAGE_F2_BINARY(name, op)                     \
  inline F2 name(const F2& a, const F2& b) {           \
    return F2(op(a.v[0], b.v[0]), op(a.v[1], b.v[1])); \
  }
PELAGE_F2_BINARY(operator+, _mm256_add_ps)
PELAGE_F2_BINARY(operator-, _mm256_sub_ps)
PELAGE_F2_BINARY(operator*, _mm256_mul_ps)
PELAGE_F2_BINARY(operator/, _mm256_div_ps)
#undef PELAGE_F2_BINARY
inline F2 sqrtOf(const F2& a) {
  return F2(_mm256_sqrt_ps(a.v[0]), _mm256_sqrt_ps(a.v[1]));
}
inline F2 floorOf(const F2& a) {
  return F2(_mm256_floor_ps(a.v[0]), _mm256_floor_ps(a.v[1]));
}
inline F2 absOf(const F2& a) {
  const __m256 sign = _mm256_set1_ps(-0.0f);
  return F2(_mm256_andnot_ps(sign, a.v[0]), _mm256_andnot_ps(sign, a.v[1]));
}
inline Mask2 greater(const F2& a, const F2& b) {
  return Mask2{
      {_mm256_cmp_ps(a.v[0], b.v[0], _CMP_GT_OQ), _mm256_cmp_ps(a.v[1], b.v[1], _CMP_GT_OQ)}};
}
inline Mask2 lessEq(const F2& a, const F2& b) {
  return Mask2{
      {_mm256_cmp_ps(a.v[0], b.v[0], _CMP_LE_OQ), _mm256_cmp_ps(a.v[1], b.v[1], _CMP_LE_OQ)}};
}
inline Mask2 equalTo(const F2& a, const F2& b) {
  return Mask2{
      {_mm256_cmp_ps(a.v[0], b.v[0], _CMP_EQ_OQ), _mm256_cmp_ps(a.v[1], b.v[1], _CMP_EQ_OQ)}};
}
inline Mask2 andMask(const Mask2& a, const Mask2& b) {
  return Mask2{{_mm256_and_ps(a.v[0], b.v[0]), _mm256_and_ps(a.v[1], b.v[1])}};
}
inline F2 pick(const Mask2& m, const F2& a, const F2& b) {
  return F2(_mm256_blendv_ps(b.v[0], a.v[0], m.v[0]), _mm256_blendv_ps(b.v[1], a.v[1], m.v[1]));
}
inline bool allOf(const Mask2& m) {
  return (_mm256_movemask_ps(m.v[0]) & _mm256_movemask_ps(m.v[1])) == 0xFF;
}

// Rows r[0..7] -> columns: out[i] lane l = r[l] lane i.
inline void transpose8(const __m256* r, __m256* out) {
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
  const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
  const __m256 s0 = _mm256_shuffle_ps(t0, t2, 0x44), s1 = _mm256_shuffle_ps(t0, t2, 0xEE);
  const __m256 s2 = _mm256_shuffle_ps(t1, t3, 0x44), s3 = _mm256_shuffle_ps(t1, t3, 0xEE);
  const __m256 s4 = _mm256_shuffle_ps(t4, t6, 0x44), s5 = _mm256_shuffle_ps(t4, t6, 0xEE);
  const __m256 s6 = _mm256_shuffle_ps(t5, t7, 0x44), s7 = _mm256_shuffle_ps(t5, t7, 0xEE);
  out[0] = _mm256_permute2f128_ps(s0, s4, 0x20);
  out[1] = _mm256_permute2f128_ps(s1, s5, 0x20);
  out[2] = _mm256_permute2f128_ps(s2, s6, 0x20);
  out[3] = _mm256_permute2f128_ps(s3, s7, 0x20);
  out[4] = _mm256_permute2f128_ps(s0, s4, 0x31);
  out[5] = _mm256_permute2f128_ps(s1, s5, 0x31);
  out[6] = _mm256_permute2f128_ps(s2, s6, 0x31);
  out[7] = _mm256_permute2f128_ps(s3, s7, 0x31);
}

// Eight 4-float rows (lane l = row l) -> four lane vectors (x, y, z, w).
inline void transpose8x4(const __m128* r, __m256& x, __m256& y, __m256& z, __m256& w) {
  const __m256 a0 = _mm256_set_m128(r[4], r[0]), a1 = _mm256_set_m128(r[5], r[1]);
  const __m256 a2 = _mm256_set_m128(r[6], r[2]), a3 = _mm256_set_m128(r[7], r[3]);
  const __m256 t0 = _mm256_unpacklo_ps(a0, a1), t1 = _mm256_unpackhi_ps(a0, a1);
  const __m256 t2 = _mm256_unpacklo_ps(a2, a3), t3 = _mm256_unpackhi_ps(a2, a3);
  x = _mm256_shuffle_ps(t0, t2, 0x44);
  y = _mm256_shuffle_ps(t0, t2, 0xEE);
  z = _mm256_shuffle_ps(t1, t3, 0x44);
  w = _mm256_shuffle_ps(t1, t3, 0xEE);
}

// Stores the first n (1..8) floats of v at p.
inline void storePartial(float* p, __m256 v, int n) {
  if (n == 8) {
    _mm256_storeu_ps(p, v);
    return;
  }
  __m128 lo = _mm256_castps256_ps128(v);
  if (n >= 4) {
    _mm_storeu_ps(p, lo);
    p += 4;
    n -= 4;
    lo = _mm256_extractf128_ps(v, 1);
  }
  if (n >= 2) {
    _mm_storel_pi(reinterpret_cast<__m64*>(p), lo);
    p += 2;
    n -= 2;
    lo = _mm_movehl_ps(lo, lo);
  }
  if (n == 1) _mm_store_ss(p, lo);
}

// The inputs of 8 hairs as lane vectors: v[0..7] = root xyz, length, normal sum xyz, (0);
// v[8..15] = direction sum xyz, (0), xi xyz, phase.
struct Lanes8 {
  __m256 v[16];
};

// Gathers 8 hairs (sec. 3.2): per hair, (b1 v1 + b2 v2) + b3 v3 (as barycentricMix) of the first 8
// floats of its triangle's three packed vertex records (position, length, normal, 0) in one ymm and
// of the last 4 (direction, 0) in one xmm, which is joined with the root's jitter; two 8 x 8
// transposes turn the rows into lanes.
inline void gather8(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                    Lanes8& out) {
  __m256 rowA[8], rowB[8];
  for (int l = 0; l < 8; ++l) {
    const std::int32_t r = roots[l];
    const float* v[3];
    triangleRecords(a, tris[l], v);
    const float* b = a.barycentric + 4 * static_cast<std::int64_t>(a.tableIndex[r]);
    const __m256 b1 = _mm256_broadcast_ss(b), b2 = _mm256_broadcast_ss(b + 1),
                 b3 = _mm256_broadcast_ss(b + 2);
    rowA[l] = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(b1, _mm256_loadu_ps(v[0])),
                                          _mm256_mul_ps(b2, _mm256_loadu_ps(v[1]))),
                            _mm256_mul_ps(b3, _mm256_loadu_ps(v[2])));
    const __m128 d =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm256_castps256_ps128(b1), _mm_loadu_ps(v[0] + 8)),
                              _mm_mul_ps(_mm256_castps256_ps128(b2), _mm_loadu_ps(v[1] + 8))),
                   _mm_mul_ps(_mm256_castps256_ps128(b3), _mm_loadu_ps(v[2] + 8)));
    rowB[l] = _mm256_insertf128_ps(_mm256_castps128_ps256(d),
                                   _mm_loadu_ps(a.jitter + 4 * static_cast<std::int64_t>(r)), 1);
  }
  transpose8(rowA, out.v);
  transpose8(rowB, out.v + 8);
}

// The twist table rows (cos, sin per point) of 8 hairs as lanes: cosAngle[p], sinAngle[p].
inline void gatherTwist8(const CoatKernelArgs& a, const std::int32_t* roots, __m256* cosAngle,
                         __m256* sinAngle) {
  __m256 rows[8], cols[8];
  for (int half = 0; half < 2; ++half) {
    for (int l = 0; l < 8; ++l)
      rows[l] = _mm256_loadu_ps(a.twist + 16 * static_cast<std::int64_t>(a.tableIndex[roots[l]]) +
                                8 * half);
    transpose8(rows, cols);
    for (int p = 0; p < 4; ++p) {
      cosAngle[4 * half + p] = cols[2 * p];
      sinAngle[4 * half + p] = cols[2 * p + 1];
    }
  }
}

// Writes lane l of v[0 .. floats) to base + l * stride for lanes l < lanes (transposed 8 x 8).
// Rows of 8 floats go out whole (non-temporal when `stream`: base and stride then 32-byte aligned).
inline void writeLanes8(float* base, std::int64_t stride, const __m256* v, int floats, int lanes,
                        bool stream) {
  for (int q = 0; 8 * q < floats; ++q) {
    __m256 cols[8], rows[8];
    for (int k = 0; k < 8; ++k) cols[k] = 8 * q + k < floats ? v[8 * q + k] : _mm256_setzero_ps();
    transpose8(cols, rows);
    const int n = floats - 8 * q < 8 ? floats - 8 * q : 8;
    if (n == 8 && stream) {
      for (int l = 0; l < lanes; ++l) _mm256_stream_ps(base + l * stride + 8 * q, rows[l]);
    } else {
      for (int l = 0; l < lanes; ++l) storePartial(base + l * stride + 8 * q, rows[l], n);
    }
  }
}

// 8 polylines' 24 floats each (three transposes), fully unrolled for a full block.
inline void writePolylines8(float* base, const __m256* v, int lanes, bool stream) {
#pragma GCC unroll 3
  for (int q = 0; q < 3; ++q) {
    __m256 rows[8];
    transpose8(v + 8 * q, rows);
    if (lanes == 8 && stream) {
      for (int l = 0; l < 8; ++l) _mm256_stream_ps(base + 24 * l + 8 * q, rows[l]);
    } else if (lanes == 8) {
      for (int l = 0; l < 8; ++l) _mm256_storeu_ps(base + 24 * l + 8 * q, rows[l]);
    } else {
      for (int l = 0; l < lanes; ++l) _mm256_storeu_ps(base + 24 * l + 8 * q, rows[l]);
    }
  }
}

// 8 lines' 6 floats each. A full block's 48 floats are contiguous (and 32-byte aligned when the
// coat's array is: blocks start at multiples of 8 hairs), so they leave as six whole vectors: rows
// r_l (6 floats each, from one transpose) are packed as r0 r1[0,1] | r1[2..5] r2[0..3] | r2[4,5] r3
// | r4 r5[0,1] | ... A partial block stores each row's 6 floats.
inline void writeLines8(float* base, const __m256* v, int lanes, bool stream) {
  const __m256 cols[8] = {
      v[0], v[1], v[2], v[3], v[4], v[5], _mm256_setzero_ps(), _mm256_setzero_ps()};
  __m256 r[8];
  transpose8(cols, r);
  if (lanes < 8) {
    for (int l = 0; l < lanes; ++l) storePartial(base + 6 * l, r[l], 6);
    return;
  }
  const __m256i first2 = _mm256_setr_epi32(0, 0, 0, 0, 0, 0, 0, 1);  // r[0,1] to slots 6, 7
  const __m256i from2 = _mm256_setr_epi32(2, 3, 4, 5, 0, 0, 0, 0);   // r[2..5] to slots 0-3
  const __m256i first4 = _mm256_setr_epi32(0, 0, 0, 0, 0, 1, 2, 3);  // r[0..3] to slots 4-7
  const __m256i from4 = _mm256_setr_epi32(4, 5, 0, 0, 0, 0, 0, 0);   // r[4,5] to slots 0, 1
  const __m256i first6 = _mm256_setr_epi32(0, 0, 0, 1, 2, 3, 4, 5);  // r[0..5] to slots 2-7
  __m256 out[6];
  for (int h = 0; h < 2; ++h) {
    const __m256* q = r + 4 * h;
    out[3 * h] = _mm256_blend_ps(q[0], _mm256_permutevar8x32_ps(q[1], first2), 0xC0);
    out[3 * h + 1] = _mm256_blend_ps(_mm256_permutevar8x32_ps(q[1], from2),
                                     _mm256_permutevar8x32_ps(q[2], first4), 0xF0);
    out[3 * h + 2] = _mm256_blend_ps(_mm256_permutevar8x32_ps(q[2], from4),
                                     _mm256_permutevar8x32_ps(q[3], first6), 0xFC);
  }
  if (stream) {
    for (int k = 0; k < 6; ++k) _mm256_stream_ps(base + 8 * k, out[k]);
  } else {
    for (int k = 0; k < 6; ++k) _mm256_storeu_ps(base + 8 * k, out[k]);
  }
}

// Stores point `s` of a block (position and normal lane vectors) into the sink arrays.
inline void storePoint(__m256* pos, __m256* nrm, int s, const Vec3<F>& p, const Vec3<F>& n) {
  pos[3 * s] = p.x.v;
  pos[3 * s + 1] = p.y.v;
  pos[3 * s + 2] = p.z.v;
  nrm[3 * s] = n.x.v;
  nrm[3 * s + 1] = n.y.v;
  nrm[3 * s + 2] = n.z.v;
}

// Writes the points of one 8-hair block: collects up to 8 points (24 position and 24 normal lane
// vectors), then writes them transposed.
struct Sink {
  const CoatKernelArgs& a;
  std::int64_t blockStart;
  int count;
  int pending = 0;    // points collected
  int groupBase = 0;  // index of the first collected point
  __m256 pos[24];
  __m256 nrm[24];
  Sink(const CoatKernelArgs& args, std::int64_t start, int n)
      : a(args), blockStart(start), count(n) {}
  void operator()(int i, const Vec3<F>& p, const Vec3<F>& n) {
    const int s = i - groupBase;
    storePoint(pos, nrm, s, p, n);
    pending = s + 1;
    if (pending == 8) flush();
  }
  void finish() {
    if (pending > 0) flush();
  }
  void flush() {
    const std::int64_t stride = 3 * static_cast<std::int64_t>(a.shape->points);
    const std::int64_t offset = blockStart * stride + 3 * groupBase;
    writeLanes8(a.positions + offset, stride, pos, 3 * pending, count, a.streamStores);
    writeLanes8(a.normals + offset, stride, nrm, 3 * pending, count, a.streamStores);
    groupBase += pending;
    pending = 0;
  }
};

// A sink for a compile-time number of points per hair (line 2, polyline 8): every index is a
// constant, so the points stay in registers or fixed stack slots and the stores are unrolled.
template <int P>
struct FixedSink {
  static_assert(P == 2 || P == 8);
  const CoatKernelArgs& a;
  std::int64_t blockStart;
  int count;
  __m256 pos[3 * P];
  __m256 nrm[3 * P];
  FixedSink(const CoatKernelArgs& args, std::int64_t start, int n)
      : a(args), blockStart(start), count(n) {}
  void operator()(int i, const Vec3<F>& p, const Vec3<F>& n) { storePoint(pos, nrm, i, p, n); }
  void finish() {
    const std::int64_t offset = blockStart * 3 * P;
    if constexpr (P == 8) {
      writePolylines8(a.positions + offset, pos, count, a.streamStores);
      writePolylines8(a.normals + offset, nrm, count, a.streamStores);
    } else {
      writeLines8(a.positions + offset, pos, count, a.streamStores);
      writeLines8(a.normals + offset, nrm, count, a.streamStores);
    }
  }
};

inline void loadTwist8(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
  __m256 c[kPolylinePoints], s[kPolylinePoints];
  gatherTwist8(a, roots, c, s);
  for (int p = 0; p < kPolylinePoints; ++p) {
    twist.cosAngle[p] = F(c[p]);
    twist.sinAngle[p] = F(s[p]);
  }
}

inline void storeIds(std::int32_t* dst, const std::int32_t* roots, int count) {
  for (int l = 0; l < count; ++l) dst[l] = roots[l];
}

// The emission half of the AVX2 and AVX-512 backends (8 lanes), and their 16-lane gather: a backend
// derives from Emission8 and adds FrameF, load (via gather16) and frameLanes (via frameHalf).
struct Emission8 {
  using F = avx2::F;
  static constexpr int kLanes = 8;
  static constexpr int kFrameLanes = 16;
  using Sink = avx2::Sink;
  template <int P>
  using FixedSink = avx2::FixedSink<P>;
  static void loadTwist(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
    loadTwist8(a, roots, twist);
  }
  static void storeIds(std::int32_t* dst, const std::int32_t* roots, int count) {
    avx2::storeIds(dst, roots, count);
  }
};

// The inputs of 16 hairs: two 8-hair gathers joined lane-wise by join(lo, hi) -> FF.
template <class FF, class Join>
inline void gather16(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                     HairInput<FF>& in, Join&& join) {
  Lanes8 lo, hi;
  gather8(a, roots, tris, lo);
  gather8(a, roots + 8, tris + 8, hi);
  const auto v = [&](int k) { return join(lo.v[k], hi.v[k]); };
  in.root = {v(0), v(1), v(2)};
  in.length = v(3);
  in.normalSum = {v(4), v(5), v(6)};
  in.directionSum = {v(8), v(9), v(10)};
  in.xi = {v(12), v(13), v(14)};
  in.phase = v(15);
}

// An 8-lane frame from a 16-lane one: half(x) -> __m256 picks the lanes from each vector.
template <class FF, class Half>
inline HairFrame<F> frameHalf(const HairFrame<FF>& f, Half&& half) {
  const auto v = [&](const FF& x) { return F(half(x)); };
  const auto v3 = [&](const Vec3<FF>& x) { return Vec3<F>{v(x.x), v(x.y), v(x.z)}; };
  return {v3(f.root),        v3(f.normal), v3(f.dTilde), v3(f.e),
          v3(f.planeNormal), v(f.length),  v(f.phase)};
}

}  // namespace
}  // namespace pelage::fur::detail::avx2
