// The AVX2 build of the hair kernel (this file alone is compiled with -mavx2; it is only called
// after a runtime check of the CPU). Gather and frame phases on 16 lanes (two ymm chains, F2),
// emission on 8: per hair, an 8-float and a 4-float barycentric mix of the packed vertex records
// (the latter joined with the root's jitter), transposed to lanes; eight points at a time
// transposed 8 x 8 so each hair's floats leave as whole 32-byte rows (non-temporal for large
// outputs).
#include "kernel_impl.h"
#include "simd_avx2.h"

namespace pelage::fur::detail {
namespace {

struct Avx2Backend : avx2::Emission8 {
  using FrameF = avx2::F2;
  static void load(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                   HairInput<FrameF>& in) {
    avx2::gather16(a, roots, tris, in, [](__m256 lo, __m256 hi) { return FrameF(lo, hi); });
  }
  static HairFrame<F> frameLanes(const HairFrame<FrameF>& f, int half) {
    return avx2::frameHalf(f, [half](const FrameF& x) { return x.v[half]; });
  }
  static FrameF loadFrame(const float* p) {
    return FrameF(_mm256_loadu_ps(p), _mm256_loadu_ps(p + 8));
  }
};

}  // namespace

void runCoatRangeAvx2(const CoatKernelArgs& args, std::int64_t begin, std::int64_t end) {
  runCoatRange<Avx2Backend>(args, begin, end);
  if (args.streamStores) _mm_sfence();
}

}  // namespace pelage::fur::detail
