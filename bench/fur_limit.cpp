// The hand-written reference kernel of bench_fur (see fur_limit.h). This file alone is compiled
// with -mavx (x86-64; elsewhere, or on a CPU without AVX, haveFurLimit() is false) and
// -ffp-contract=off.
#include "fur_limit.h"

#include "pelage/fur/roots.h"
#include "pelage/util/parallel.h"

#if defined(__x86_64__) && defined(__AVX__)
#include <immintrin.h>

#include <algorithm>
#include <cstring>

namespace pelage::bench {
namespace {

using fur::HairFrame;
using fur::HairInput;
using fur::HairTwist;
using fur::Vec3;

// Four hairs in one __m128 (F4) or eight in one __m256 (F8), with the lane helpers hair_math.h
// asks for (IEEE only).
#define PELAGE_LIMIT_LANES(F, M, R, ps, all)                                            \
  struct F {                                                                            \
    R v;                                                                                \
    F() = default;                                                                      \
    F(float x) : v(ps(set1)(x)) {} /* NOLINT(google-explicit-constructor): broadcast */ \
    explicit F(R x) : v(x) {}                                                           \
  };                                                                                    \
  struct M {                                                                            \
    R v;                                                                                \
  };                                                                                    \
  inline F operator+(F a, F b) {                                                        \
    return F(ps(add)(a.v, b.v));                                                        \
  }                                                                                     \
  inline F operator-(F a, F b) {                                                        \
    return F(ps(sub)(a.v, b.v));                                                        \
  }                                                                                     \
  inline F operator*(F a, F b) {                                                        \
    return F(ps(mul)(a.v, b.v));                                                        \
  }                                                                                     \
  inline F operator/(F a, F b) {                                                        \
    return F(ps(div)(a.v, b.v));                                                        \
  }                                                                                     \
  inline F sqrtOf(F a) {                                                                \
    return F(ps(sqrt)(a.v));                                                            \
  }                                                                                     \
  inline F floorOf(F a) {                                                               \
    return F(ps(floor)(a.v));                                                           \
  }                                                                                     \
  inline F absOf(F a) {                                                                 \
    return F(ps(andnot)(ps(set1)(-0.0f), a.v));                                         \
  }                                                                                     \
  inline M andMask(M a, M b) {                                                          \
    return M{ps(and)(a.v, b.v)};                                                        \
  }                                                                                     \
  inline F pick(M m, F a, F b) {                                                        \
    return F(ps(blendv)(b.v, a.v, m.v));                                                \
  }                                                                                     \
  inline bool allOf(M m) {                                                              \
    return ps(movemask)(m.v) == (all);                                                  \
  }
#define PELAGE_PS4(op) _mm_##op##_ps
#define PELAGE_PS8(op) _mm256_##op##_ps
PELAGE_LIMIT_LANES(F4, M4, __m128, PELAGE_PS4, 0xF)
PELAGE_LIMIT_LANES(F8, M8, __m256, PELAGE_PS8, 0xFF)
#undef PELAGE_LIMIT_LANES
#undef PELAGE_PS4
#undef PELAGE_PS8
inline M4 greater(F4 a, F4 b) {
  return M4{_mm_cmpgt_ps(a.v, b.v)};
}
inline M4 lessEq(F4 a, F4 b) {
  return M4{_mm_cmple_ps(a.v, b.v)};
}
inline M4 equalTo(F4 a, F4 b) {
  return M4{_mm_cmpeq_ps(a.v, b.v)};
}
inline M8 greater(F8 a, F8 b) {
  return M8{_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)};
}
inline M8 lessEq(F8 a, F8 b) {
  return M8{_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)};
}
inline M8 equalTo(F8 a, F8 b) {
  return M8{_mm256_cmp_ps(a.v, b.v, _CMP_EQ_OQ)};
}

// Sixteen hairs as two __m256 side by side: the frame phase's long sqrt/div chains of one half
// hide behind the other's.
struct F16 {
  __m256 v[2];
  F16() = default;
  F16(float x) : v{_mm256_set1_ps(x), _mm256_set1_ps(x)} {}  // NOLINT: broadcast
  F16(__m256 a, __m256 b) : v{a, b} {}
};
struct M16 {
  __m256 v[2];
};
#define PELAGE_F16(name, op)                            \
  inline F16 name(const F16& a, const F16& b) {         \
    return F16(op(a.v[0], b.v[0]), op(a.v[1], b.v[1])); \
  }
PELAGE_F16(operator+, _mm256_add_ps)
PELAGE_F16(operator-, _mm256_sub_ps)
PELAGE_F16(operator*, _mm256_mul_ps)
PELAGE_F16(operator/, _mm256_div_ps)
#undef PELAGE_F16
inline F16 sqrtOf(const F16& a) {
  return F16(_mm256_sqrt_ps(a.v[0]), _mm256_sqrt_ps(a.v[1]));
}
inline F16 floorOf(const F16& a) {
  return F16(_mm256_floor_ps(a.v[0]), _mm256_floor_ps(a.v[1]));
}
inline F16 absOf(const F16& a) {
  const __m256 s = _mm256_set1_ps(-0.0f);
  return F16(_mm256_andnot_ps(s, a.v[0]), _mm256_andnot_ps(s, a.v[1]));
}
#define PELAGE_M16(name, pred)                                                              \
  inline M16 name(const F16& a, const F16& b) {                                             \
    return M16{{_mm256_cmp_ps(a.v[0], b.v[0], pred), _mm256_cmp_ps(a.v[1], b.v[1], pred)}}; \
  }
PELAGE_M16(greater, _CMP_GT_OQ)
PELAGE_M16(lessEq, _CMP_LE_OQ)
PELAGE_M16(equalTo, _CMP_EQ_OQ)
#undef PELAGE_M16
inline M16 andMask(const M16& a, const M16& b) {
  return M16{{_mm256_and_ps(a.v[0], b.v[0]), _mm256_and_ps(a.v[1], b.v[1])}};
}
inline F16 pick(const M16& m, const F16& a, const F16& b) {
  return F16(_mm256_blendv_ps(b.v[0], a.v[0], m.v[0]), _mm256_blendv_ps(b.v[1], a.v[1], m.v[1]));
}
inline bool allOf(const M16& m) {
  return (_mm256_movemask_ps(m.v[0]) & _mm256_movemask_ps(m.v[1])) == 0xFF;
}

// Lanes from 4-hair quarters, and quarter g of lanes.
inline F4 join(const __m128* q, F4*) {
  return F4(q[0]);
}
inline F8 join(const __m128* q, F8*) {
  return F8(_mm256_set_m128(q[1], q[0]));
}
inline F16 join(const __m128* q, F16*) {
  return F16(_mm256_set_m128(q[1], q[0]), _mm256_set_m128(q[3], q[2]));
}
// Emission lanes j of frame lanes.
inline F4 part(const F4& x, int) {
  return x;
}
inline F8 part(const F8& x, int) {
  return x;
}
inline F8 part(const F16& x, int j) {
  return F8(x.v[j]);
}
template <class E, class FF>
inline HairFrame<E> framePart(const HairFrame<FF>& f, int j) {
  const auto v = [j](const FF& x) { return part(x, j); };
  const auto v3 = [&](const Vec3<FF>& x) { return Vec3<E>{v(x.x), v(x.y), v(x.z)}; };
  return {v3(f.root),  v3(f.normal), v3(f.dTilde),    v3(f.e),        v3(f.planeNormal),
          v(f.length), v(f.phase),   v(f.curlRadius), v(f.curlTurns), v(f.widthScale)};
}
inline __m128 quarter(const F4& x, int) {
  return x.v;
}
inline __m128 quarter(const F8& x, int g) {
  return g == 0 ? _mm256_castps256_ps128(x.v) : _mm256_extractf128_ps(x.v, 1);
}

// Hairs `roots[0..4)`' inputs as 16 columns: per hair, (b1 v1 + b2 v2) + b3 v3 of the three
// 4-float quarters of its triangle's vertex records, and its jitter; one transpose per quarter.
inline void gather4(const float* records, const std::int32_t* triangles, const fur::FurRoots& fr,
                    const fur::CoatRoots& cr, const std::int64_t* roots, __m128 (&q)[4][4]) {
  for (int h = 0; h < 4; ++h) {  // q[quarter][hair], then [quarter][column]
    const std::int64_t r = roots[h];
    const std::int32_t* tv = triangles + 3 * static_cast<std::int64_t>(cr.triangle[r]);
    const float* v0 = records + fur::kVertexRecordFloats * static_cast<std::int64_t>(tv[0]);
    const float* v1 = records + fur::kVertexRecordFloats * static_cast<std::int64_t>(tv[1]);
    const float* v2 = records + fur::kVertexRecordFloats * static_cast<std::int64_t>(tv[2]);
    const float* b = fr.barycentric.data() + 4 * static_cast<std::int64_t>(cr.tableIndex[r]);
    const __m128 b1 = _mm_set1_ps(b[0]), b2 = _mm_set1_ps(b[1]), b3 = _mm_set1_ps(b[2]);
    for (int k = 0; k < 3; ++k)
      q[k][h] = _mm_add_ps(_mm_add_ps(_mm_mul_ps(b1, _mm_loadu_ps(v0 + 4 * k)),
                                      _mm_mul_ps(b2, _mm_loadu_ps(v1 + 4 * k))),
                           _mm_mul_ps(b3, _mm_loadu_ps(v2 + 4 * k)));
    q[3][h] = _mm_loadu_ps(cr.jitter.data() + 4 * r);
  }
  for (auto& quarter : q) _MM_TRANSPOSE4_PS(quarter[0], quarter[1], quarter[2], quarter[3]);
}

// The inputs of W = sizeof(F) / 4 hairs (W / 4 gathers of 4).
template <class F>
inline void gather(const float* records, const std::int32_t* triangles, const fur::FurRoots& fr,
                   const fur::CoatRoots& cr, const std::int64_t* roots, HairInput<F>& in) {
  constexpr int kQuarters = sizeof(F) / 16;
  __m128 q[kQuarters][4][4];
  for (int g = 0; g < kQuarters; ++g) gather4(records, triangles, fr, cr, roots + 4 * g, q[g]);
  const auto col = [&](int quarter, int c) {
    __m128 parts[kQuarters];
    for (int g = 0; g < kQuarters; ++g) parts[g] = q[g][quarter][c];
    return join(parts, static_cast<F*>(nullptr));
  };
  in.root = {col(0, 0), col(0, 1), col(0, 2)};
  in.length = col(0, 3);
  in.normalSum = {col(1, 0), col(1, 1), col(1, 2)};
  in.directionSum = {col(2, 0), col(2, 1), col(2, 2)};
  in.xi = {col(3, 0), col(3, 1), col(3, 2)};
  in.phase = col(3, 3);
}

template <class F>
inline void twist(const float* table, const fur::CoatRoots& cr, const std::int64_t* roots,
                  HairTwist<F>& out) {
  constexpr int kQuarters = sizeof(F) / 16;
  for (int k = 0; k < 4; ++k) {
    __m128 r[kQuarters][4];
    for (int g = 0; g < kQuarters; ++g) {
      for (int h = 0; h < 4; ++h)
        r[g][h] = _mm_loadu_ps(
            table + 16 * static_cast<std::int64_t>(cr.tableIndex[roots[4 * g + h]]) + 4 * k);
      _MM_TRANSPOSE4_PS(r[g][0], r[g][1], r[g][2], r[g][3]);
    }
    const auto col = [&](int c) {
      __m128 parts[kQuarters];
      for (int g = 0; g < kQuarters; ++g) parts[g] = r[g][c];
      return join(parts, static_cast<F*>(nullptr));
    };
    out.cosAngle[2 * k] = col(0);
    out.sinAngle[2 * k] = col(1);
    out.cosAngle[2 * k + 1] = col(2);
    out.sinAngle[2 * k + 1] = col(3);
  }
}

// Collects a block's P points (position and normal columns), then writes each hair's 3 P floats.
template <class F, int P>
struct Sink {
  F pos[3 * P];
  F nrm[3 * P];
  void operator()(int i, const Vec3<F>& p, const Vec3<F>& n) {
    pos[3 * i] = p.x;
    pos[3 * i + 1] = p.y;
    pos[3 * i + 2] = p.z;
    nrm[3 * i] = n.x;
    nrm[3 * i + 1] = n.y;
    nrm[3 * i + 2] = n.z;
  }
};

template <bool kStream>
inline void put(float* p, __m128 v) {
  if constexpr (kStream)
    _mm_stream_ps(p, v);
  else
    _mm_storeu_ps(p, v);
}

// Writes 4 hairs' columns cols[0 .. 3 P) to out (hair h at h 3 P), whole 4-float rows.
template <int P, bool kStream>
inline void write4(float* out, __m128* cols) {
  if constexpr (P == 2) {  // 4 lines' 24 contiguous floats as six rows
    __m128 z = _mm_setzero_ps(), w = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(cols[0], cols[1], cols[2], cols[3]);
    _MM_TRANSPOSE4_PS(cols[4], cols[5], z, w);
    put<kStream>(out, cols[0]);
    put<kStream>(out + 4, _mm_movelh_ps(cols[4], cols[1]));
    put<kStream>(out + 8, _mm_shuffle_ps(cols[1], cols[5], _MM_SHUFFLE(1, 0, 3, 2)));
    put<kStream>(out + 12, cols[2]);
    put<kStream>(out + 16, _mm_movelh_ps(z, cols[3]));
    put<kStream>(out + 20, _mm_shuffle_ps(cols[3], w, _MM_SHUFFLE(1, 0, 3, 2)));
  } else {
    static_assert(P % 4 == 0);
    for (int f = 0; f < 3 * P; f += 4) {
      _MM_TRANSPOSE4_PS(cols[f], cols[f + 1], cols[f + 2], cols[f + 3]);
      for (int h = 0; h < 4; ++h) put<kStream>(out + h * 3 * P + f, cols[f + h]);
    }
  }
}

// Writes hairs [0, n) of a block of W = sizeof(F) / 4 (4 at a time; the coat's last hairs
// through a buffer).
template <int P, bool kStream, class F>
inline void writeBlock(float* out, const F* cols, std::int64_t n) {
  for (int g = 0; 4 * g < n && g < static_cast<int>(sizeof(F) / 16); ++g) {
    __m128 c[3 * P];
    for (int k = 0; k < 3 * P; ++k) c[k] = quarter(cols[k], g);
    float* o = out + 4 * g * 3 * P;
    if (n - 4 * g >= 4) {
      write4<P, kStream>(o, c);
    } else {
      alignas(16) float rows[4 * 3 * P];
      write4<P, false>(rows, c);
      std::memcpy(o, rows, static_cast<std::size_t>((n - 4 * g) * 3 * P) * sizeof(float));
    }
  }
}

// The frame and emission loops are functions of their own (each gets its own registers).
template <class FF>
__attribute__((noinline)) void frames(const fur::CoatShape& shape, const HairInput<FF>* in,
                                      HairFrame<FF>* f, int blocks) {
  for (int k = 0; k < blocks; ++k) fur::hairFrame(shape, in[k], f[k]);
}

template <class F, int P, bool kStream, class FF, std::size_t W>
__attribute__((noinline)) void emit(const fur::CoatShape& shape, const fur::CoatRoots& cr,
                                    const float* twistTable, const std::int64_t (*roots)[W],
                                    const HairFrame<FF>* f, std::int64_t chunk, std::int64_t end,
                                    int blocks, float* positions, float* normals) {
  constexpr int E = sizeof(F) / 4, kSplit = static_cast<int>(W) / E;
  for (int k = 0; k < blocks * kSplit; ++k) {
    const std::int64_t i = chunk + E * k;
    if (i >= end) break;
    const HairFrame<F> fk = framePart<F>(f[k / kSplit], k % kSplit);
    Sink<F, P> sink;
    if constexpr (P == 2) {
      fur::emitLine(fk, sink);
    } else {
      HairTwist<F> tw;
      if (shape.twist) twist(twistTable, cr, roots[k / kSplit] + E * (k % kSplit), tw);
      fur::emitPolyline(shape, fk, tw, sink);
    }
    writeBlock<P, kStream>(positions + i * 3 * P, sink.pos, end - i);
    writeBlock<P, kStream>(normals + i * 3 * P, sink.nrm, end - i);
  }
}

// Frames in FF lanes (W hairs), emission in F lanes (E hairs).
template <class FF, class F, int P, bool kStream>
void runCoat(const fur::CoatShape& shape, const float* records, const std::int32_t* triangles,
             const fur::FurRoots& fr, const fur::CoatRoots& cr, const float* twistTable,
             float* positions, float* normals, std::int64_t begin, std::int64_t end) {
  constexpr int W = sizeof(FF) / 4;
  const std::int64_t n = cr.size();
  // Chunks of 64 hairs in three loops (gather, frames, emission) whose data stays in L1, so the
  // core overlaps the long sqrt/div chains of neighbouring blocks.
  constexpr int kBlocks = 64 / W;
  HairInput<FF> in[kBlocks];
  HairFrame<FF> f[kBlocks];
  std::int64_t roots[kBlocks][W];
  for (std::int64_t chunk = begin; chunk < end; chunk += W * kBlocks) {
    const int blocks = static_cast<int>(std::min<std::int64_t>(kBlocks, (end - chunk + W - 1) / W));
    for (int k = 0; k < blocks; ++k) {
      for (int h = 0; h < W; ++h) {
        const std::int64_t r = chunk + W * k + h;
        roots[k][h] = r < n ? r : n - 1;
      }
      gather(records, triangles, fr, cr, roots[k], in[k]);
    }
    frames(shape, in, f, blocks);
    emit<F, P, kStream>(shape, cr, twistTable, roots, f, chunk, end, blocks, positions, normals);
  }
  if constexpr (kStream) _mm_sfence();
}

}  // namespace

bool haveFurLimit() {
  return __builtin_cpu_supports("avx") != 0;
}

bool furLimitCovers(const fur::FurParams& params, const fur::FurRoots& roots) {
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const fur::HairStyle s = params.coats[ci].style;
    if (s != fur::HairStyle::Line && s != fur::HairStyle::Polyline) return false;
    if (!roots.coats[ci].lengthScale.empty()) return false;
  }
  return true;
}

namespace {
template <class FF, class F>
void limitFrame(const skin::SkinMesh& skin, const fur::FurRoots& roots,
                const fur::FurParams& params, const skin::DeformedSkin& deformed, FurLimitWork& w) {
  const std::int64_t nV = skin.numVertices();
  w.records.resize(static_cast<std::size_t>(nV * fur::kVertexRecordFloats));
  const float* len = skin.furLengths();
  float* o = w.records.data();
  parallelForChunks(nV, 8192, [&](std::int64_t b, std::int64_t e) {
    for (std::int64_t v = b; v < e; ++v) {
      const auto sv = static_cast<std::size_t>(v);
      const float r[fur::kVertexRecordFloats] = {
          deformed.positions[sv].x(),  deformed.positions[sv].y(),
          deformed.positions[sv].z(),  len[v],
          deformed.normals[sv].x(),    deformed.normals[sv].y(),
          deformed.normals[sv].z(),    0.0f,
          deformed.directions[sv].x(), deformed.directions[sv].y(),
          deformed.directions[sv].z(), 0.0f};
      std::memcpy(o + v * fur::kVertexRecordFloats, r, sizeof r);
    }
  });
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    const fur::CoatRoots& cr = roots.coats[ci];
    const fur::CoatShape shape = fur::makeCoatShape(params, c);
    if (shape.twist && w.twist[ci].empty())
      fur::makeTwistTable(fur::coatSeed(roots.seed, c), params.coats[ci].normalRandomize,
                          w.twist[ci]);
    const std::int64_t n = cr.size();
    const auto floats = static_cast<std::size_t>(n * shape.points * 3);
    w.positions[ci].resize(floats);
    w.normals[ci].resize(floats);
    const bool stream = static_cast<double>(floats) * 8.0 > 8.0 * 1024.0 * 1024.0;
    float* pos = w.positions[ci].data();
    float* nrm = w.normals[ci].data();
    const float* twist = w.twist[ci].data();
    parallelForChunks(n, 4096, [&](std::int64_t b, std::int64_t e) {
      const bool line = shape.style == fur::HairStyle::Line;
      if (line && stream)
        runCoat<FF, F, 2, true>(shape, o, skin.triangles.data(), roots, cr, twist, pos, nrm, b, e);
      else if (line)
        runCoat<FF, F, 2, false>(shape, o, skin.triangles.data(), roots, cr, twist, pos, nrm, b, e);
      else if (stream)
        runCoat<FF, F, 8, true>(shape, o, skin.triangles.data(), roots, cr, twist, pos, nrm, b, e);
      else
        runCoat<FF, F, 8, false>(shape, o, skin.triangles.data(), roots, cr, twist, pos, nrm, b, e);
    });
  }
}
}  // namespace

void furLimitFrame(const skin::SkinMesh& skin, const fur::FurRoots& roots,
                   const fur::FurParams& params, const skin::DeformedSkin& deformed,
                   FurLimitWork& w, int width) {
  if (width == 16)
    limitFrame<F16, F8>(skin, roots, params, deformed, w);
  else if (width == 8)
    limitFrame<F8, F8>(skin, roots, params, deformed, w);
  else
    limitFrame<F4, F4>(skin, roots, params, deformed, w);
}

}  // namespace pelage::bench

#else  // not x86-64: no reference

namespace pelage::bench {
bool haveFurLimit() {
  return false;
}
bool furLimitCovers(const fur::FurParams&, const fur::FurRoots&) {
  return false;
}
void furLimitFrame(const skin::SkinMesh&, const fur::FurRoots&, const fur::FurParams&,
                   const skin::DeformedSkin&, FurLimitWork&, int) {}
}  // namespace pelage::bench

#endif
