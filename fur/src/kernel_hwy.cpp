// The per-frame hair kernel (kernel_impl.h) on Google Highway: one source compiled for every target
// Highway builds on this machine (x86-64: SSSE3, SSE4, AVX2, AVX-512 and the scalar baseline;
// aarch64: NEON), the best one the CPU has picked at run time (HWY_DYNAMIC_DISPATCH). Its lane
// types use only IEEE add, sub, mul, div, sqrt, compares, selects and floor (no FMA, no
// approximations; the file is compiled with -ffp-contract=off), so every target gives the scalar
// reference's bits (hair_math.h with T = float).
//
// Layout (structure of arrays; lanes are hairs): the gather and frame phases run on 16 hairs, the
// emission on 8 (kLanes). A hair's inputs (its triangle's three 12-float vertex records mixed by
// its barycentric weights, and its 4-float jitter) are built as four 4-float rows and turned into
// lanes by 4 x 4 transposes; points leave the same way, each hair's floats as whole 4-float rows
// (non-temporal for large outputs). No hardware gathers: they are slow on AMD's Zen cores.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "kernel_hwy.cpp"
// SVE's and RVV's vectors are sizeless and cannot be members of the lane structs below: aarch64
// CPUs with SVE run the NEON target. The sanitizer builds (PELAGE_KERNEL_FEW_TARGETS) compile each
// lane layout once: scalar, 4 floats per vector (SSE4) and 8 (AVX2); SSSE3 and AVX-512 repeat
// SSE4's and AVX2's layouts and would take minutes more to compile instrumented (they run in the
// other builds' tests).
#ifdef PELAGE_KERNEL_FEW_TARGETS
#define PELAGE_KERNEL_REPEATED_LAYOUTS (HWY_SSSE3 | HWY_AVX3 | HWY_AVX3_DL)
#else
#define PELAGE_KERNEL_REPEATED_LAYOUTS 0
#endif
#ifndef HWY_DISABLED_TARGETS
#define HWY_DISABLED_TARGETS \
  (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV | PELAGE_KERNEL_REPEATED_LAYOUTS)
#endif
#include <hwy/cache_control.h>
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "kernel_impl.h"
#include "pelage/fur/generate.h"

HWY_BEFORE_NAMESPACE();
namespace pelage::fur::detail {
namespace HWY_NAMESPACE {
namespace {
namespace hn = hwy::HWY_NAMESPACE;

// Floats per Highway vector in the lane types: the target's width, at most 8 (1 on HWY_SCALAR).
// The AVX-512 target thus runs 256-bit vectors (AVX-512VL, 32 registers): Zen 4 executes 512-bit
// operations as two 256-bit halves, and the 16-hair frames already give two independent chains.
#if HWY_TARGET == HWY_SCALAR
inline constexpr int kVecFloats = 1;
#else
inline constexpr int kVecFloats = HWY_MAX_BYTES / 4 < 8 ? HWY_MAX_BYTES / 4 : 8;
#endif

template <int N>
struct LaneMask;

// N floats (hairs) as N / kPer Highway vectors of kPer lanes. Its operations (below) are found by
// argument-dependent lookup from hair_math.h's templates. They are plain `inline`, not
// always-inline: the phase functions of Backend and RunCoatRange below are `flatten`, which inlines
// what they call (hair_math.h's templates, compiled for no particular target, and these) into
// functions of the target.
template <int N>
struct Lanes {
  static constexpr int kPer = N < kVecFloats ? N : kVecFloats;
  static constexpr int kCount = N / kPer;
  using D = hn::FixedTag<float, kPer>;
  using V = hn::Vec<D>;
  V v[kCount];

  // (Constructors written out, not defaulted: an implicit one would not be compiled for the target,
  // and Highway's NEON vectors' constructors are always-inline.)
  Lanes() {}
  Lanes(float x) {  // NOLINT(google-explicit-constructor): broadcast, like T(1.0f) for float
    for (V& e : v) e = hn::Set(D(), x);
  }
};

#define PELAGE_LANES_BINARY(op)                                           \
  template <int N>                                                        \
  inline Lanes<N> operator op(const Lanes<N>& a, const Lanes<N>& b) {     \
    Lanes<N> r;                                                           \
    for (int i = 0; i < Lanes<N>::kCount; ++i) r.v[i] = a.v[i] op b.v[i]; \
    return r;                                                             \
  }
PELAGE_LANES_BINARY(+)
PELAGE_LANES_BINARY(-)
PELAGE_LANES_BINARY(*)
PELAGE_LANES_BINARY(/)
#undef PELAGE_LANES_BINARY
#define PELAGE_LANES_UNARY(name, fn)                                    \
  template <int N>                                                      \
  inline Lanes<N> name(const Lanes<N>& a) {                             \
    Lanes<N> r;                                                         \
    for (int i = 0; i < Lanes<N>::kCount; ++i) r.v[i] = hn::fn(a.v[i]); \
    return r;                                                           \
  }
PELAGE_LANES_UNARY(sqrtOf, Sqrt)
PELAGE_LANES_UNARY(floorOf, Floor)
PELAGE_LANES_UNARY(absOf, Abs)
#undef PELAGE_LANES_UNARY
#define PELAGE_LANES_COMPARE(name, op)                                    \
  template <int N>                                                        \
  inline LaneMask<N> name(const Lanes<N>& a, const Lanes<N>& b) {         \
    LaneMask<N> m;                                                        \
    for (int i = 0; i < Lanes<N>::kCount; ++i) m.m[i] = a.v[i] op b.v[i]; \
    return m;                                                             \
  }
PELAGE_LANES_COMPARE(greater, >)
PELAGE_LANES_COMPARE(lessEq, <=)
PELAGE_LANES_COMPARE(equalTo, ==)
#undef PELAGE_LANES_COMPARE

template <int N>
struct LaneMask {
  LaneMask() {}
  hn::Mask<typename Lanes<N>::D> m[Lanes<N>::kCount];
};

template <int N>
inline Lanes<N> pick(const LaneMask<N>& m, const Lanes<N>& a, const Lanes<N>& b) {
  Lanes<N> r;
  for (int i = 0; i < Lanes<N>::kCount; ++i) r.v[i] = hn::IfThenElse(m.m[i], a.v[i], b.v[i]);
  return r;
}
template <int N>
inline LaneMask<N> andMask(const LaneMask<N>& a, const LaneMask<N>& b) {
  LaneMask<N> r;
  for (int i = 0; i < Lanes<N>::kCount; ++i) r.m[i] = hn::And(a.m[i], b.m[i]);
  return r;
}
template <int N>
inline bool allOf(const LaneMask<N>& a) {
  bool all = true;
  for (int i = 0; i < Lanes<N>::kCount; ++i)
    all = all && hn::AllTrue(typename Lanes<N>::D(), a.m[i]);
  return all;
}

using F = Lanes<kLanes>;                // emission blocks
inline constexpr int kFrameLanes = 16;  // gather and frame blocks
using FrameF = Lanes<kFrameLanes>;

template <int N>
inline Lanes<N> loadLanes(const float* p) {
  Lanes<N> r;
  for (int i = 0; i < Lanes<N>::kCount; ++i)
    r.v[i] = hn::LoadU(typename Lanes<N>::D(), p + i * Lanes<N>::kPer);
  return r;
}

// Lanes [8 j, 8 j + 8) of 16.
inline F eightOf(const FrameF& x, int j) {
  static_assert(FrameF::kPer == F::kPer);
  F r;
  for (int i = 0; i < F::kCount; ++i) r.v[i] = x.v[j * F::kCount + i];
  return r;
}

// A hair's inputs from the 16 columns of its gathered row, col(c): root xyz, length, normal sum
// xyz, (0), direction sum xyz, (0), jitter xyz, phase.
template <class Col>
inline void setInputs(Col&& col, HairInput<FrameF>& in) {
  in.root = {col(0), col(1), col(2)};
  in.length = col(3);
  in.normalSum = {col(4), col(5), col(6)};
  in.directionSum = {col(8), col(9), col(10)};
  in.xi = {col(12), col(13), col(14)};
  in.phase = col(15);
}

#if HWY_TARGET == HWY_SCALAR
// The scalar target (x86-64 CPUs without SSSE3): lane-wise gathers and stores through arrays.
template <int N>
inline void storeLanes(const Lanes<N>& x, float* p) {
  for (int i = 0; i < N; ++i) p[i] = hn::GetLane(x.v[i]);
}

inline void gather16(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                     HairInput<FrameF>& in) {
  float cols[16][kFrameLanes];
  for (int l = 0; l < kFrameLanes; ++l) {
    const std::int32_t r = roots[l];
    const float* v[3];
    triangleRecords(a, tris[l], v);
    const HairInput<float> h =
        interpolateRoot(a.barycentric + 4 * static_cast<std::int64_t>(a.tableIndex[r]), v[0], v[1],
                        v[2], a.jitter + 4 * static_cast<std::int64_t>(r));
    const float row[16] = {h.root.x,         h.root.y,         h.root.z,         h.length,
                           h.normalSum.x,    h.normalSum.y,    h.normalSum.z,    0.0f,
                           h.directionSum.x, h.directionSum.y, h.directionSum.z, 0.0f,
                           h.xi.x,           h.xi.y,           h.xi.z,           h.phase};
    for (int c = 0; c < 16; ++c) cols[c][l] = row[c];
  }
  setInputs([&](int c) { return loadLanes<kFrameLanes>(cols[c]); }, in);
}

inline void loadTwist8(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
  float c[kPolylinePoints][kLanes], s[kPolylinePoints][kLanes];
  for (int l = 0; l < kLanes; ++l) {
    const float* tw = a.twist + 16 * static_cast<std::int64_t>(a.tableIndex[roots[l]]);
    for (int p = 0; p < kPolylinePoints; ++p) {
      c[p][l] = tw[2 * p];
      s[p][l] = tw[2 * p + 1];
    }
  }
  for (int p = 0; p < kPolylinePoints; ++p) {
    twist.cosAngle[p] = loadLanes<kLanes>(c[p]);
    twist.sinAngle[p] = loadLanes<kLanes>(s[p]);
  }
}

// Writes lane l of cols[0 .. floats) to base + l * stride for lanes l < lanes.
inline void writeColumns(float* base, std::int64_t stride, const F* cols, int floats, int lanes) {
  for (int f = 0; f < floats; ++f) {
    float x[kLanes];
    storeLanes(cols[f], x);
    for (int l = 0; l < lanes; ++l) base[l * stride + f] = x[l];
  }
}

template <int Floats>
inline void writeBlock(float* base, std::int64_t stride, const F* cols, int lanes, bool) {
  writeColumns(base, stride, cols, Floats, lanes);
}
#else
using D4 = hn::FixedTag<float, 4>;
using V4 = hn::Vec<D4>;

// Rows r0..r3 -> columns c0..c3 (c_k lane h = r_h lane k).
inline void transpose4(const V4* r, V4* c) {
  const D4 d;
  const V4 t0 = hn::InterleaveLower(d, r[0], r[1]);  // r00 r10 r01 r11
  const V4 t1 = hn::InterleaveLower(d, r[2], r[3]);  // r20 r30 r21 r31
  const V4 t2 = hn::InterleaveUpper(d, r[0], r[1]);  // r02 r12 r03 r13
  const V4 t3 = hn::InterleaveUpper(d, r[2], r[3]);  // r22 r32 r23 r33
  c[0] = hn::ConcatLowerLower(d, t1, t0);
  c[1] = hn::ConcatUpperUpper(d, t1, t0);
  c[2] = hn::ConcatLowerLower(d, t3, t2);
  c[3] = hn::ConcatUpperUpper(d, t3, t2);
}

// Lanes [4 j, 4 j + 4) of x.
template <int N>
inline V4 quarterOf(const Lanes<N>& x, int j) {
  constexpr int kPer = Lanes<N>::kPer;
  static_assert(kPer == 4 || kPer == 8);
  if constexpr (kPer == 4) {
    return x.v[j];
  } else {
    const auto& v = x.v[j / 2];
    return j % 2 == 0 ? hn::LowerHalf(v) : hn::UpperHalf(D4(), v);
  }
}

// Lanes of N floats from N / 4 quarters.
template <int N>
inline Lanes<N> fromQuarters(const V4* q) {
  constexpr int kPer = Lanes<N>::kPer;
  Lanes<N> r;
  for (int i = 0; i < Lanes<N>::kCount; ++i) {
    static_assert(kPer == 4 || kPer == 8);
    if constexpr (kPer == 4) {
      r.v[i] = q[i];
    } else {
      r.v[i] = hn::Combine(typename Lanes<N>::D(), q[2 * i + 1], q[2 * i]);
    }
  }
  return r;
}

// Gathers 16 hairs (sec. 3.2): per hair, (b1 v1 + b2 v2) + b3 v3 (as barycentricMix) of the 12
// floats of its triangle's three packed vertex records (position, length, normal, 0, direction, 0)
// as three 4-float rows, and the root's jitter as a fourth; 4 x 4 transposes turn them into lanes.
inline void gather16(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                     HairInput<FrameF>& in) {
  const D4 d;
  V4 cols[16][kFrameLanes / 4];  // column c (float c of the 16-float row), quarter g
  for (int g = 0; g < kFrameLanes / 4; ++g) {
    V4 rows[4][4];  // [piece][hair]
    for (int h = 0; h < 4; ++h) {
      const std::int32_t r = roots[4 * g + h];
      const float* v[3];
      triangleRecords(a, tris[4 * g + h], v);
      const float* b = a.barycentric + 4 * static_cast<std::int64_t>(a.tableIndex[r]);
      const V4 b1 = hn::Set(d, b[0]), b2 = hn::Set(d, b[1]), b3 = hn::Set(d, b[2]);
      for (int q = 0; q < 3; ++q)
        rows[q][h] = (b1 * hn::LoadU(d, v[0] + 4 * q) + b2 * hn::LoadU(d, v[1] + 4 * q)) +
                     b3 * hn::LoadU(d, v[2] + 4 * q);
      rows[3][h] = hn::LoadU(d, a.jitter + 4 * static_cast<std::int64_t>(r));
    }
    for (int q = 0; q < 4; ++q) {
      V4 c[4];
      transpose4(rows[q], c);
      for (int k = 0; k < 4; ++k) cols[4 * q + k][g] = c[k];
    }
  }
  setInputs([&](int c) { return fromQuarters<kFrameLanes>(cols[c]); }, in);
}

// The twist table rows (cos, sin per point: 16 floats) of 8 hairs as lanes.
inline void loadTwist8(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
  const D4 d;
  V4 cols[16][kLanes / 4];
  for (int g = 0; g < kLanes / 4; ++g) {
    const float* row[4];
    for (int h = 0; h < 4; ++h)
      row[h] = a.twist + 16 * static_cast<std::int64_t>(a.tableIndex[roots[4 * g + h]]);
    for (int q = 0; q < 4; ++q) {
      V4 r[4], c[4];
      for (int h = 0; h < 4; ++h) r[h] = hn::LoadU(d, row[h] + 4 * q);
      transpose4(r, c);
      for (int k = 0; k < 4; ++k) cols[4 * q + k][g] = c[k];
    }
  }
  for (int p = 0; p < kPolylinePoints; ++p) {
    twist.cosAngle[p] = fromQuarters<kLanes>(cols[2 * p]);
    twist.sinAngle[p] = fromQuarters<kLanes>(cols[2 * p + 1]);
  }
}

// Stores the first n (1..4) floats of v at p.
inline void storeFirst(V4 v, int n, float* p) {
  if (n == 4) {
    hn::StoreU(v, D4(), p);
    return;
  }
  if (n >= 2) hn::StoreU(hn::LowerHalf(v), hn::FixedTag<float, 2>(), p);
  if (n != 2) p[n - 1] = hn::ExtractLane(v, static_cast<std::size_t>(n - 1));
}

// Writes lane l of cols[0 .. floats) to base + l * stride for lanes l < lanes: 4 columns by 4 hairs
// at a time, transposed, so each hair's floats leave as 4-float rows (partial blocks and groups).
inline void writeColumns(float* base, std::int64_t stride, const F* cols, int floats, int lanes) {
  for (int f = 0; f < floats; f += 4) {
    const int n = floats - f < 4 ? floats - f : 4;
    for (int g = 0; 4 * g < lanes; ++g) {
      V4 c[4], r[4];
      for (int k = 0; k < 4; ++k) c[k] = k < n ? quarterOf(cols[f + k], g) : hn::Zero(D4());
      transpose4(c, r);
      const int hairs = lanes - 4 * g < 4 ? lanes - 4 * g : 4;
      for (int h = 0; h < hairs; ++h) storeFirst(r[h], n, base + (4 * g + h) * stride + f);
    }
  }
}

// A full block's (kLanes hairs') `Floats` floats per hair, every index a constant: whole 4-float
// rows (non-temporal when Stream; base and stride then keep them 16-byte aligned). A line's 6
// floats are packed so that 4 lines (24 contiguous floats) leave as six whole rows.
template <int Floats, bool Stream>
inline void writeFullBlock(float* base, std::int64_t stride, const F* cols) {
  const D4 d;
  const auto put = [&](V4 v, float* p) {
    if constexpr (Stream)
      hn::Stream(v, d, p);
    else
      hn::StoreU(v, d, p);
  };
  if constexpr (Floats == 6) {
    for (int g = 0; g < kLanes / 4; ++g) {
      V4 c[4], a[4], b[4];
      for (int k = 0; k < 4; ++k) c[k] = quarterOf(cols[k], g);
      transpose4(c, a);  // a[h]: floats 0-3 of hair h
      c[0] = quarterOf(cols[4], g);
      c[1] = quarterOf(cols[5], g);
      c[2] = c[3] = hn::Zero(d);
      transpose4(c, b);  // b[h] lanes 0-1: floats 4-5 of hair h
      float* p = base + 24 * g;
      put(a[0], p);
      put(hn::ConcatLowerLower(d, a[1], b[0]), p + 4);
      put(hn::ConcatLowerUpper(d, b[1], a[1]), p + 8);
      put(a[2], p + 12);
      put(hn::ConcatLowerLower(d, a[3], b[2]), p + 16);
      put(hn::ConcatLowerUpper(d, b[3], a[3]), p + 20);
    }
  } else {
    static_assert(Floats % 4 == 0);
    // Four hairs at a time, so that few of the output's cache lines are open at once.
#pragma GCC unroll 4
    for (int g = 0; g < kLanes / 4; ++g)
#pragma GCC unroll 64
      for (int f = 0; f < Floats; f += 4) {
        V4 c[4], r[4];
        for (int k = 0; k < 4; ++k) c[k] = quarterOf(cols[f + k], g);
        transpose4(c, r);
        for (int h = 0; h < 4; ++h) put(r[h], base + (4 * g + h) * stride + f);
      }
  }
}

// Writes `Floats` columns of a block of `lanes` hairs (see writeFullBlock and writeColumns).
template <int Floats>
inline void writeBlock(float* base, std::int64_t stride, const F* cols, int lanes, bool stream) {
  if constexpr (Floats % 4 == 0 || Floats == 6) {
    if (lanes == kLanes) {
      if (stream)
        writeFullBlock<Floats, true>(base, stride, cols);
      else
        writeFullBlock<Floats, false>(base, stride, cols);
      return;
    }
  }
  writeColumns(base, stride, cols, Floats, lanes);
}
#endif

// Writes the points of one emission block: collects G points (3 G position and 3 G normal lane
// vectors), then writes them transposed; the last group may be shorter (finish()). kWhole: G is
// every point of the hair (a constant stride).
template <int G, bool kWhole>
struct BlockSink {
  const CoatKernelArgs& a;
  std::int64_t blockStart;
  int count;
  int pending = 0;    // points collected
  int groupBase = 0;  // index of the first collected point
  F pos[3 * G];
  F nrm[3 * G];
  BlockSink(const CoatKernelArgs& args, std::int64_t start, int n)
      : a(args), blockStart(start), count(n) {}
  void operator()(int i, const Vec3<F>& p, const Vec3<F>& n) {
    const int s = i - groupBase;
    pos[3 * s] = p.x;
    pos[3 * s + 1] = p.y;
    pos[3 * s + 2] = p.z;
    nrm[3 * s] = n.x;
    nrm[3 * s + 1] = n.y;
    nrm[3 * s + 2] = n.z;
    pending = s + 1;
    if (pending == G) flush();
  }
  void finish() {
    if (pending > 0) flush();
  }
  void flush() {
    const std::int64_t stride = kWhole ? 3 * G : 3 * static_cast<std::int64_t>(a.shape->points);
    const std::int64_t offset = blockStart * stride + 3 * groupBase;
    if (pending == G) {
      writeBlock<3 * G>(a.positions + offset, stride, pos, count, a.streamStores);
      writeBlock<3 * G>(a.normals + offset, stride, nrm, count, a.streamStores);
    } else {
      writeColumns(a.positions + offset, stride, pos, 3 * pending, count);
      writeColumns(a.normals + offset, stride, nrm, 3 * pending, count);
    }
    groupBase += pending;
    pending = 0;
  }
};

struct Backend {
  using F = HWY_NAMESPACE::F;
  using FrameF = HWY_NAMESPACE::FrameF;
  static constexpr int kLanes = detail::kLanes;
  static constexpr int kFrameLanes = HWY_NAMESPACE::kFrameLanes;
  // Any number of points: groups of 8 (24 floats, whole 4-float rows); a line's 2 or a
  // polyline's 8 points are written at once.
  using Sink = BlockSink<8, false>;
  template <int P>
  using FixedSink = BlockSink<P, true>;

  static void load(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                   HairInput<FrameF>& in) {
    gather16(a, roots, tris, in);
  }
  static FrameF loadFrame(const float* p) { return loadLanes<kFrameLanes>(p); }
  static HairFrame<F> frameLanes(const HairFrame<FrameF>& f, int j) {
    const auto v = [j](const FrameF& x) { return eightOf(x, j); };
    const auto v3 = [&](const Vec3<FrameF>& x) { return Vec3<F>{v(x.x), v(x.y), v(x.z)}; };
    return {v3(f.root),  v3(f.normal), v3(f.dTilde),    v3(f.e),        v3(f.planeNormal),
            v(f.length), v(f.phase),   v(f.curlRadius), v(f.curlTurns), v(f.widthScale)};
  }
  static void loadTwist(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
    loadTwist8(a, roots, twist);
  }
  static void storeIds(std::int32_t* dst, const std::int32_t* roots, int count) {
    std::memcpy(dst, roots, static_cast<std::size_t>(count) * sizeof(std::int32_t));
  }
  // The phases, each one function of this target (everything inlined into it, see Lanes).
  __attribute__((flatten, noinline)) static void frames(const CoatShape& shape,
                                                        const HairInput<FrameF>* inputs,
                                                        HairFrame<FrameF>* out, int blocks) {
    framePhase(shape, inputs, out, blocks);
  }
  __attribute__((flatten, noinline)) static void dynamics(const CoatShape& shape,
                                                          const CoatDynamicsArgs& d,
                                                          const std::int32_t* roots, int count,
                                                          HairFrame<FrameF>* out, int blocks) {
    dynamicsPhase<kFrameLanes>(shape, d, roots, count, out, blocks);
  }
  template <HairStyle S>
  __attribute__((flatten, noinline)) static void emit(const CoatKernelArgs& a,
                                                      const HairFrame<FrameF>* f, int blocks,
                                                      int lastCount, std::int64_t chunkStart,
                                                      const std::int32_t* roots) {
    emitPhase<Backend, S>(a, f, blocks, lastCount, chunkStart, roots);
  }
};

}  // namespace

// This target's kernel: everything inlined into it (see Lanes).
__attribute__((flatten)) void RunCoatRange(const CoatKernelArgs& args, std::int64_t begin,
                                           std::int64_t end) {
  runCoatRange<Backend>(args, begin, end);
  if (args.streamStores) hwy::FlushStream();
}

}  // namespace HWY_NAMESPACE
}  // namespace pelage::fur::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace pelage::fur {
namespace detail {

HWY_EXPORT(RunCoatRange);

void runCoatRange(const CoatKernelArgs& args, std::int64_t begin, std::int64_t end) {
  HWY_DYNAMIC_DISPATCH(RunCoatRange)(args, begin, end);
}

}  // namespace detail

namespace {
// The targets compiled here that the CPU runs, best first; read before any forcing (setKernelTarget
// asks for them first).
const std::vector<std::int64_t>& cpuTargets() {
  static const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets;
}
// A target as users know it: Highway's AVX3 family is AVX-512.
std::string targetName(std::int64_t t) {
  const std::string name = hwy::TargetName(t);
  if (name == "AVX3") return "AVX-512";
  if (name.rfind("AVX3_", 0) == 0) return "AVX-512_" + name.substr(5);
  return name;
}
}  // namespace

std::vector<std::string> kernelTargets() {
  std::vector<std::string> names;
  for (const std::int64_t t : cpuTargets()) names.emplace_back(targetName(t));
  return names;
}

bool setKernelTarget(const std::string& name) {
  const std::vector<std::int64_t>& targets = cpuTargets();
  if (name.empty() || name == "auto") {
    hwy::SetSupportedTargetsForTest(0);
    return true;
  }
  for (const std::int64_t t : targets)
    if (name == targetName(t)) {
      hwy::SetSupportedTargetsForTest(t);
      return true;
    }
  return false;
}

std::string activeKernelTarget() {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  return targets.empty() ? std::string("?") : targetName(targets.front());
}

}  // namespace pelage::fur
#endif  // HWY_ONCE
