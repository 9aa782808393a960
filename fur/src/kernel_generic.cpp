// The generic (x86-64 baseline / any CPU) build of the hair kernel: lane-wise loops, scalar gathers
// and stores. Bit-identical to the AVX2 build.
#include "kernel_impl.h"
#include "simd_generic.h"

namespace pelage::fur::detail {
namespace {

struct GenericBackend {
  using F = generic::F;
  using FrameF = generic::F;
  static constexpr int kLanes = detail::kLanes;
  static constexpr int kFrameLanes = detail::kLanes;

  static const HairFrame<F>& frameLanes(const HairFrame<F>& f, int) { return f; }
  static FrameF loadFrame(const float* p) {
    F r;
    for (int l = 0; l < kLanes; ++l) r.v[l] = p[l];
    return r;
  }

  static void load(const CoatKernelArgs& a, const std::int32_t* roots, const std::int32_t* tris,
                   HairInput<F>& in) {
    for (int l = 0; l < kLanes; ++l) {
      const std::int32_t r = roots[l];
      const float* v[3];
      triangleRecords(a, tris[l], v);
      const HairInput<float> h =
          interpolateRoot(a.barycentric + 4 * static_cast<std::int64_t>(a.tableIndex[r]), v[0],
                          v[1], v[2], a.jitter + 4 * static_cast<std::int64_t>(r));
      in.root.x.v[l] = h.root.x;
      in.root.y.v[l] = h.root.y;
      in.root.z.v[l] = h.root.z;
      in.length.v[l] = h.length;
      in.normalSum.x.v[l] = h.normalSum.x;
      in.normalSum.y.v[l] = h.normalSum.y;
      in.normalSum.z.v[l] = h.normalSum.z;
      in.directionSum.x.v[l] = h.directionSum.x;
      in.directionSum.y.v[l] = h.directionSum.y;
      in.directionSum.z.v[l] = h.directionSum.z;
      in.xi.x.v[l] = h.xi.x;
      in.xi.y.v[l] = h.xi.y;
      in.xi.z.v[l] = h.xi.z;
      in.phase.v[l] = h.phase;
    }
  }

  static void loadTwist(const CoatKernelArgs& a, const std::int32_t* roots, HairTwist<F>& twist) {
    for (int l = 0; l < kLanes; ++l) {
      const float* tw = a.twist + 16 * static_cast<std::int64_t>(a.tableIndex[roots[l]]);
      for (int p = 0; p < kPolylinePoints; ++p) {
        twist.cosAngle[p].v[l] = tw[2 * p];
        twist.sinAngle[p].v[l] = tw[2 * p + 1];
      }
    }
  }

  // Writes point i of every real lane straight to its hair's place.
  struct Sink {
    const CoatKernelArgs& a;
    std::int64_t blockStart;
    int count;
    Sink(const CoatKernelArgs& args, std::int64_t start, int n)
        : a(args), blockStart(start), count(n) {}
    void operator()(int i, const Vec3<F>& p, const Vec3<F>& n) {
      const std::int64_t P = a.shape->points;
      for (int l = 0; l < count; ++l) {
        const std::int64_t o = ((blockStart + l) * P + i) * 3;
        a.positions[o] = p.x.v[l];
        a.positions[o + 1] = p.y.v[l];
        a.positions[o + 2] = p.z.v[l];
        a.normals[o] = n.x.v[l];
        a.normals[o + 1] = n.y.v[l];
        a.normals[o + 2] = n.z.v[l];
      }
    }
    void finish() {}
  };

  template <int P>
  using FixedSink = Sink;

  static void storeIds(std::int32_t* dst, const std::int32_t* roots, int count) {
    for (int l = 0; l < count; ++l) dst[l] = roots[l];
  }
};

}  // namespace

void runCoatRangeGeneric(const CoatKernelArgs& args, std::int64_t begin, std::int64_t end) {
  runCoatRange<GenericBackend>(args, begin, end);
}

}  // namespace pelage::fur::detail
