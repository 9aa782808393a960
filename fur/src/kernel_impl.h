// The per-frame hair kernel, written once over a backend B that supplies the lane types (B::FrameF
// for the gather and frame phases, B::F for the emission), the gather of a block's inputs (B::load)
// and the transposed stores (B::Sink, B::FixedSink<P>). Included by kernel_hwy.cpp only, whose
// per-target backends instantiate it; everything here has internal linkage.
//
// Layout: SIMD lanes are hairs (structure of arrays); drawn hairs are taken in chunks of 128,
// processed in three loops (gather, frame, emission) whose data stays in L1; roots are sorted by
// triangle, so a block mostly reads one or two triangles' vertex records; each hair's P points are
// written contiguously (hair i at i * P).
#pragma once

#include <cstdint>

#include "dynamics_kernel.h"
#include "kernel.h"
#include "pelage/fur/hair_math.h"

namespace pelage::fur::detail {
namespace {

// The triangle holding drawn hair `i`: the last t with drawnStart[t] <= i (never an empty one).
inline std::int32_t triangleOfDrawn(const std::int32_t* drawnStart, std::int32_t nT,
                                    std::int64_t i) {
  std::int32_t lo = 0, hi = nT;  // answer in [lo, hi)
  while (hi - lo > 1) {
    const std::int32_t mid = lo + (hi - lo) / 2;
    if (drawnStart[mid] <= i)
      lo = mid;
    else
      hi = mid;
  }
  while (drawnStart[lo + 1] <= i) ++lo;  // skip triangles that draw nothing
  return lo;
}

// Hairs per chunk: three short loops run over a chunk whose inputs and frames stay in L1 (about
// 16 KB), so the out-of-order core overlaps the independent sqrt/div chains of neighbouring blocks
// instead of waiting on one block's long chain.
inline constexpr int kChunkHairs = 128;

// Runs emit(k, frame of block k, sink) for the chunk's emission blocks of B::kLanes lanes.
template <class B, class Sink, class FrameF, class Emit>
void emitBlocks(const CoatKernelArgs& a, const HairFrame<FrameF>* frames, int blocks, int lastCount,
                std::int64_t start, Emit&& emit) {
  constexpr int L = B::kLanes, kRatio = B::kFrameLanes / B::kLanes;
  for (int k = 0; k < blocks; ++k) {
    Sink sink(a, start + static_cast<std::int64_t>(k) * L, k + 1 == blocks ? lastCount : L);
    emit(k, B::frameLanes(frames[k / kRatio], k % kRatio), sink);
    sink.finish();
  }
}

// The phases a backend runs as separate (not inlined) functions: each is a few hundred vector
// instructions, which keeps the register allocation of one phase apart from the others'.
// 2. Frames: directions, gravity, hair plane (sec. 3.4, 3.5, 3.7).
template <class FrameF>
void framePhase(const CoatShape& shape, const HairInput<FrameF>* inputs, HairFrame<FrameF>* frames,
                int blocks) {
  for (int k = 0; k < blocks; ++k) hairFrame(shape, inputs[k], frames[k]);
}

// 2b. Fur dynamics: damped ending points (dynamics_kernel.h), only when asked for.
template <int kFrameLanes, class FrameF>
void dynamicsPhase(const CoatShape& shape, const CoatDynamicsArgs& d, const std::int32_t* roots,
                   int count, HairFrame<FrameF>* frames, int blocks) {
  for (int k = 0; k < blocks; ++k)
    dynamicEnds(shape, d, roots + k * kFrameLanes,
                count - k * kFrameLanes < kFrameLanes ? count - k * kFrameLanes : kFrameLanes,
                frames[k]);
}

// 3. Points and normals of the coat's style S, stored transposed (sec. 3.6 to 3.8), for the
// chunk's `blocks` emission blocks (the last with `lastCount` hairs) from `chunkStart`.
template <class B, HairStyle S>
void emitPhase(const CoatKernelArgs& a, const HairFrame<typename B::FrameF>* frames, int blocks,
               int lastCount, std::int64_t chunkStart, const std::int32_t* roots) {
  using F = typename B::F;
  const CoatShape& shape = *a.shape;
  if constexpr (S == HairStyle::Line) {
    emitBlocks<B, typename B::template FixedSink<2>>(
        a, frames, blocks, lastCount, chunkStart,
        [&](int, const HairFrame<F>& f, typename B::template FixedSink<2>& s) { emitLine(f, s); });
  } else if constexpr (S == HairStyle::Polyline) {
    emitBlocks<B, typename B::template FixedSink<kPolylinePoints>>(
        a, frames, blocks, lastCount, chunkStart,
        [&](int k, const HairFrame<F>& f, typename B::template FixedSink<kPolylinePoints>& s) {
          HairTwist<F> twist;
          if (shape.twist) B::loadTwist(a, roots + k * B::kLanes, twist);
          emitPolyline(shape, f, twist, s);
        });
  } else if constexpr (S == HairStyle::Curve) {
    emitBlocks<B, typename B::Sink>(
        a, frames, blocks, lastCount, chunkStart,
        [&](int, const HairFrame<F>& f, typename B::Sink& s) { emitCurve(shape, f, s); });
  } else {
    emitBlocks<B, typename B::Sink>(
        a, frames, blocks, lastCount, chunkStart,
        [&](int, const HairFrame<F>& f, typename B::Sink& s) { emitTube(shape, f, s); });
  }
}

// B::FrameF (B::kFrameLanes lanes) runs the gather and frame phases, B::F (B::kLanes lanes) the
// emission; B::frameLanes(frame, j) is block j of kLanes lanes of a frame. B::frames, B::dynamics
// and B::emit<S> run framePhase, dynamicsPhase and emitPhase<B, S>.
template <class B>
void runCoatRange(const CoatKernelArgs& a, std::int64_t begin, std::int64_t end) {
  using FrameF = typename B::FrameF;
  constexpr int kLanes = B::kLanes;            // hairs per emission block
  constexpr int kFrameLanes = B::kFrameLanes;  // hairs per gather/frame block
  constexpr int kFrameBlocks = kChunkHairs / kFrameLanes;
  static_assert(kChunkHairs % kFrameLanes == 0 && kFrameLanes % kLanes == 0);
  const CoatShape& shape = *a.shape;
  if (begin >= end) return;
  // Walk the drawn hairs in order: hair i is root r of triangle t.
  std::int32_t t = a.allDrawn ? 0 : triangleOfDrawn(a.drawnStart, a.triangleCount, begin);
  std::int32_t r =
      a.allDrawn ? 0 : a.triangleStart[t] + static_cast<std::int32_t>(begin - a.drawnStart[t]);
  std::int64_t i = begin;
  std::int32_t roots[kChunkHairs];
  std::int32_t tris[kChunkHairs];
  HairInput<FrameF> inputs[kFrameBlocks];
  HairFrame<FrameF> frames[kFrameBlocks];
  while (i < end) {
    const std::int64_t chunkStart = i;
    const int count = end - i < kChunkHairs ? static_cast<int>(end - i) : kChunkHairs;
    if (a.allDrawn) {  // no culling: drawn hair i is root i
      for (int l = 0; l < count; ++l) {
        roots[l] = static_cast<std::int32_t>(i + l);
        tris[l] = a.rootTriangle[i + l];
      }
      i += count;
    } else {
      for (int l = 0; l < count; ++l) {
        roots[l] = r;
        tris[l] = t;
        ++i;
        if (i < end) {
          if (i == a.drawnStart[t + 1]) {
            do ++t;
            while (a.drawnStart[t + 1] == i);
            r = a.triangleStart[t];
          } else {
            ++r;
          }
        }
      }
    }
    // Padding lanes repeat the last hair; they are computed but never stored.
    const int frameBlocks = (count + kFrameLanes - 1) / kFrameLanes;
    for (int l = count; l < frameBlocks * kFrameLanes; ++l) {
      roots[l] = roots[count - 1];
      tris[l] = tris[count - 1];
    }
    const int blocks = (count + kLanes - 1) / kLanes;
    const int lastCount = count - (blocks - 1) * kLanes;
    // 1. Gather: interpolate every hair's root data (sec. 3.2); a length map scales the
    // interpolated length (interpolateRoot's lengthScale).
    for (int k = 0; k < frameBlocks; ++k)
      B::load(a, roots + k * kFrameLanes, tris + k * kFrameLanes, inputs[k]);
    if (a.lengthScale)
      for (int k = 0; k < frameBlocks; ++k) {
        float s[kFrameLanes];
        for (int l = 0; l < kFrameLanes; ++l) s[l] = a.lengthScale[roots[k * kFrameLanes + l]];
        inputs[k].length = inputs[k].length * B::loadFrame(s);
      }
    // A groom's stiffness, segment direction weight, curl and width: each root's own floppiness,
    // w, helix and width scale (CoatRoots::floppiness, ::segmentWeight, ::curlRadius, ::curlTurns,
    // ::widthScale).
    const auto gatherPerRoot = [&](const float* values, auto member) {
      if (!values) return;
      for (int k = 0; k < frameBlocks; ++k) {
        float f[kFrameLanes];
        for (int l = 0; l < kFrameLanes; ++l) f[l] = values[roots[k * kFrameLanes + l]];
        inputs[k].*member = B::loadFrame(f);
      }
    };
    gatherPerRoot(a.floppiness, &HairInput<FrameF>::floppiness);
    gatherPerRoot(a.segmentWeight, &HairInput<FrameF>::segmentWeight);
    gatherPerRoot(a.curlRadius, &HairInput<FrameF>::curlRadius);
    gatherPerRoot(a.curlTurns, &HairInput<FrameF>::curlTurns);
    gatherPerRoot(a.widthScale, &HairInput<FrameF>::widthScale);
    // A groom's comb: each hair's first triangle edge and unpacked comb (interpolateRoot's).
    if (a.comb)
      for (int k = 0; k < frameBlocks; ++k) {
        float cols[5][kFrameLanes];
        for (int l = 0; l < kFrameLanes; ++l) {
          const float* v[3];
          triangleRecords(a, tris[k * kFrameLanes + l], v);
          for (int x = 0; x < 3; ++x) cols[x][l] = v[1][x] - v[0][x];
          unpackComb(a.comb[roots[k * kFrameLanes + l]], cols[3][l], cols[4][l]);
        }
        inputs[k].combEdge = {B::loadFrame(cols[0]), B::loadFrame(cols[1]), B::loadFrame(cols[2])};
        inputs[k].combX = B::loadFrame(cols[3]);
        inputs[k].combY = B::loadFrame(cols[4]);
      }
    // 2. Frames, 2b. dynamics, 3. emission (the phases above, through the backend).
    B::frames(shape, inputs, frames, frameBlocks);
    if (a.dynamics) B::dynamics(shape, *a.dynamics, roots, count, frames, frameBlocks);
    if (!a.emit) continue;
    switch (shape.style) {
      case HairStyle::Line:
        B::template emit<HairStyle::Line>(a, frames, blocks, lastCount, chunkStart, roots);
        break;
      case HairStyle::Polyline:
        B::template emit<HairStyle::Polyline>(a, frames, blocks, lastCount, chunkStart, roots);
        break;
      case HairStyle::Curve:
        B::template emit<HairStyle::Curve>(a, frames, blocks, lastCount, chunkStart, roots);
        break;
      case HairStyle::Tube:
        B::template emit<HairStyle::Tube>(a, frames, blocks, lastCount, chunkStart, roots);
        break;
    }
    B::storeIds(a.hairIds + chunkStart, roots, count);
  }
}

}  // namespace
}  // namespace pelage::fur::detail
