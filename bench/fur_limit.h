// The "limit" of bench_fur: the best hand-written kernel of the same per-frame fur work that I
// could write for the x86-64 machines pelage is measured on, to compare pelage's Highway kernel
// against in the same run. Same work: pack the deformed skin's vertex records, then for every root
// of both coats interpolate its inputs (sec. 3.2), build its frame (sec. 3.4, 3.5, 3.7) and emit
// its line or polyline (sec. 3.6, 3.7) with hair_math.h's formulas, into the same arrays, bit for
// bit. Written directly in intrinsics, structure of arrays: 4 hairs per __m128 (SSE), 8 per __m256
// (AVX), or frames on 16 (two __m256) and emission on 8; _MM_TRANSPOSE4_PS gathers and stores,
// chunks of 64 hairs, no dispatch and no abstraction. Only what bench_fur times: every hair drawn
// (no culling), no dynamics, no length maps, lines and polylines.
#pragma once

#include <array>

#include "pelage/fur/generate.h"

namespace pelage::bench {

// Whether this build and CPU have the reference (x86-64 with AVX).
bool haveFurLimit();

struct FurLimitWork {
  std::vector<float> records;                 // packed vertex records (kVertexRecordFloats each)
  std::array<std::vector<float>, 2> twist;    // per coat (polylines with normal randomisation)
  std::array<fur::FloatBuffer, 2> positions;  // per coat, hair i at i P 3
  std::array<fur::FloatBuffer, 2> normals;
};

// Whether the reference computes this frame (see the header comment); false otherwise.
bool furLimitCovers(const fur::FurParams& params, const fur::FurRoots& roots);

// One frame of the reference, `width` hairs per frame block (4: SSE, 8: AVX, 16: AVX pairs).
// `work` keeps its buffers between calls.
void furLimitFrame(const skin::SkinMesh& skin, const fur::FurRoots& roots,
                   const fur::FurParams& params, const skin::DeformedSkin& deformed,
                   FurLimitWork& work, int width);

}  // namespace pelage::bench
