// Per-frame fur on the default monkey (130k triangles), Van Gelder & Wilhelms 1997 sec. 3: the
// fig9 preset (overcoat + undercoat, every randomisation on) with both coats in one style, 500,000
// hairs, culling off, the skin deformed once outside the timed loop. Targets (issue 3, 2 threads):
// polyline <= 4 ms/frame (125 M hairs/s), line <= 2 ms/frame; curve and tube are reported.
// Arguments: style (0 line, 1 polyline, 2 curve, 3 tube), threads, hairs, kernel (0 auto = the
// best the CPU has, 1 generic, 2 AVX2, 3 AVX-512; skipped where the CPU lacks it).
#include <benchmark/benchmark.h>

#include "pelage/anatomy/creature.h"
#include "pelage/anatomy/pose.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/models/builtin.h"
#include "pelage/skin/build_from_shapes.h"
#include "pelage/skin/deform.h"
#include "pelage/util/parallel.h"

namespace {

using namespace pelage;

// The default monkey (built-in creature, default skin of ~130k triangles).
struct Monkey {
  anatomy::Body body;
  skin::SkinMesh skin;
};
const Monkey& monkey() {
  static const Monkey m = [] {
    const anatomy::Creature c =
        anatomy::parseCreature(std::string(*models::builtinFile("monkey.json")), "built-in monkey");
    return Monkey{c.body, skin::buildSkin(c, {c.defaultTriangles})};
  }();
  return m;
}

void BM_FurFrame(benchmark::State& st) {
  const auto style = static_cast<fur::HairStyle>(st.range(0));
  const int threads = static_cast<int>(st.range(1));
  const double hairs = static_cast<double>(st.range(2));
  const fur::KernelPath paths[] = {fur::KernelPath::Auto, fur::KernelPath::Generic,
                                   fur::KernelPath::Avx2, fur::KernelPath::Avx512};
  setThreadCount(threads);
  if (!fur::setKernelPath(paths[st.range(3)])) {
    st.SkipWithError("the CPU lacks this kernel path");
    return;
  }
  const Monkey& m = monkey();
  fur::FurParams params = fur::loadFurPreset("fig9");
  params.hairs = hairs;
  for (auto& c : params.coats) c.style = style;
  const fur::FurRoots roots = fur::growRoots(m.skin, params);
  anatomy::BodyState state;
  anatomy::forwardKinematics(m.body, anatomy::restPose(m.body), state);
  skin::DeformedSkin deformed;
  skin::deformSkin(m.skin, state, deformed);
  fur::FurWorkspace ws;
  fur::FurFrame frame;
  const fur::FurView view;                                             // culling off: every hair
  fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);  // sizes the buffers
  for (auto _ : st) {
    fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);
    benchmark::DoNotOptimize(frame.coats[0].positions.data());
    benchmark::ClobberMemory();
  }
  const double n = static_cast<double>(frame.drawn());
  st.counters["hairs"] = n;
  st.counters["threads"] = threads;
  st.counters["hairs/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  st.counters["MB/frame"] =
      static_cast<double>(frame.coats[0].drawn * frame.coats[0].layout.pointsPerHair() +
                          frame.coats[1].drawn * frame.coats[1].layout.pointsPerHair()) *
      24.0 / 1e6;
  st.SetLabel(std::string(fur::styleName(style)) + " " +
              fur::kernelPathName(fur::activeKernelPath()));
  fur::setKernelPath(fur::KernelPath::Auto);
}

void styles(benchmark::internal::Benchmark* b) {
  for (int style = 0; style < 4; ++style)
    for (int threads : {1, 2}) b->Args({style, threads, 500000, 0});
  for (int kernel : {1, 2, 3})  // each kernel path, for comparison
    for (int style : {0, 1}) b->Args({style, 2, 500000, kernel});
}
BENCHMARK(BM_FurFrame)->Apply(styles)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
