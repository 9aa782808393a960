// The per-frame hair kernel's inputs (kernel_impl.h, compiled per SIMD target by kernel_hwy.cpp).
// Plain pointers and PODs only, no Eigen: nothing here is compiled for a particular target.
#pragma once

#include <cstdint>

#include "pelage/fur/hair_math.h"

namespace pelage::fur::detail {

// Hairs per SIMD block of the emission phase.
inline constexpr int kLanes = 8;

struct CoatDynamicsArgs;  // dynamics_kernel.h

struct CoatKernelArgs {
  const CoatShape* shape = nullptr;
  const float* vertices = nullptr;              // nV x 12 (kVertexRecordFloats), 16-byte aligned
  const std::int32_t* triangles = nullptr;      // nT x 3
  const std::int32_t* triangleStart = nullptr;  // nT + 1: roots of each triangle
  const std::int32_t* drawnStart = nullptr;     // nT + 1: drawn hairs of each triangle
  std::int32_t triangleCount = 0;
  bool allDrawn = false;                       // no culling: drawnStart == triangleStart
  const std::int32_t* rootTriangle = nullptr;  // nRoots: each root's triangle
  const std::uint16_t* tableIndex = nullptr;   // nRoots
  const float* jitter = nullptr;               // nRoots x 4
  const float* lengthScale = nullptr;          // nRoots (a length map), or null
  const std::uint32_t* comb = nullptr;         // nRoots (a groom's comb, packComb), or null
  const float* floppiness = nullptr;           // nRoots (a groom's stiffness), or null
  const float* segmentWeight = nullptr;        // nRoots (a groom's direction weight), or null
  const float* curlRadius = nullptr;           // nRoots (a groom's curl), or null
  const float* curlTurns = nullptr;            // nRoots (with curlRadius), or null
  const float* widthScale = nullptr;           // nRoots (a groom's width scale, tubes), or null
  const float* barycentric = nullptr;          // 2048 x 4
  const float* twist = nullptr;                // 2048 x 16 (cos, sin per point) or null
  float* positions = nullptr;                  // drawn x P x 3
  float* normals = nullptr;                    // drawn x P x 3
  std::int32_t* hairIds = nullptr;             // drawn
  bool streamStores = false;  // non-temporal stores (large outputs; P a multiple of 8, or lines)
  // Fur dynamics (dynamics_kernel.h): per-hair damped ends replacing the gravity droop, or null
  // for the paper's quasi-static hairs. With `emit` false only the dynamic state is advanced
  // (positions, normals and hairIds may be null).
  const CoatDynamicsArgs* dynamics = nullptr;
  bool emit = true;
};

namespace {
// The packed vertex records of triangle t's three vertices.
inline void triangleRecords(const CoatKernelArgs& a, std::int32_t t, const float* v[3]) {
  const std::int32_t* tv = a.triangles + 3 * static_cast<std::int64_t>(t);
  for (int k = 0; k < 3; ++k)
    v[k] = a.vertices + kVertexRecordFloats * static_cast<std::int64_t>(tv[k]);
}
}  // namespace

// Computes drawn hairs [begin, end) (begin a multiple of 16, so SIMD blocks and their stores stay
// aligned) with the best SIMD target the CPU has (or the one setKernelTarget forced).
void runCoatRange(const CoatKernelArgs& args, std::int64_t begin, std::int64_t end);

}  // namespace pelage::fur::detail
