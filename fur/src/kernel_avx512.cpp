// The AVX-512 build of the hair kernel (compiled with -mavx512f -mavx512dq -mavx512vl; called only
// after a runtime check): gather and frame phases on 16 lanes in zmm registers (each hair's inputs
// mixed as one zmm row, 16 rows transposed at once), emission on 8 lanes with the AVX2 code (which
// gets 32 ymm registers here).
#include "kernel_impl.h"
#include "simd_avx2.h"
#include "simd_avx512.h"

namespace pelage::fur::detail {
namespace {

struct Avx512Backend : avx2::Emission8 {
  using FrameF = avx512::F;
  static void load(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                   HairInput<FrameF>& in) {
    avx512::gather16(a, roots, tris, in);
  }
  static HairFrame<F> frameLanes(const HairFrame<FrameF>& f, int half) {
    return avx2::frameHalf(f, [half](const FrameF& x) { return avx512::half(x.v, half); });
  }
  static FrameF loadFrame(const float* p) { return FrameF(_mm512_loadu_ps(p)); }
};

}  // namespace

void runCoatRangeAvx512(const CoatKernelArgs& args, std::int64_t begin, std::int64_t end) {
  runCoatRange<Avx512Backend>(args, begin, end);
  if (args.streamStores) _mm_sfence();
}

}  // namespace pelage::fur::detail
