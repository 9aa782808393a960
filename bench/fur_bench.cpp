// Per-frame fur on the default monkey (130k triangles), Van Gelder & Wilhelms 1997 sec. 3: the
// fig9 preset (overcoat + undercoat, every randomisation on) with both coats in one style, 500,000
// hairs, culling off, the skin deformed once outside the timed loop. Targets (issue 3, 2 threads):
// polyline <= 4 ms/frame (125 M hairs/s), line <= 2 ms/frame; curve and tube are reported.
// Arguments: style (0 line, 1 polyline, 2 curve, 3 tube), threads, hairs, kernel target (0 auto =
// the best the CPU has, k = the k-th of fur::kernelTargets(), best first; skipped where absent).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "fur_limit.h"
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
const Monkey& monkey();

// The monkey's rest pose, deformed once (outside any timed loop).
const skin::DeformedSkin& restSkin() {
  static const skin::DeformedSkin d = [] {
    const Monkey& m = monkey();
    anatomy::BodyState state;
    anatomy::forwardKinematics(m.body, anatomy::restPose(m.body), state);
    skin::DeformedSkin out;
    skin::deformSkin(m.skin, state, out);
    return out;
  }();
  return d;
}

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
  const std::vector<std::string> targets = fur::kernelTargets();
  const auto target = static_cast<std::size_t>(st.range(3));
  setThreadCount(threads);
  if (target > targets.size() ||
      !fur::setKernelTarget(target == 0 ? "auto" : targets[target - 1])) {
    st.SkipWithError("the CPU lacks this kernel target");
    return;
  }
  const Monkey& m = monkey();
  fur::FurParams params = fur::loadFurPreset("fig9");
  params.setHairCount(hairs);
  for (auto& c : params.coats) c.style = style;
  const fur::FurRoots roots = fur::growRoots(m.skin, params);
  const skin::DeformedSkin& deformed = restSkin();
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
  st.SetLabel(std::string(fur::styleName(style)) + " " + fur::activeKernelTarget());
  fur::setKernelTarget("auto");
}

void styles(benchmark::internal::Benchmark* b) {
  for (int style = 0; style < 4; ++style)
    for (int threads : {1, 2}) b->Args({style, threads, 500000, 0});
  for (int kernel : {1, 2, 3, 4, 5})  // each kernel target, for comparison
    for (int style : {0, 1}) b->Args({style, 2, 500000, kernel});
}
BENCHMARK(BM_FurFrame)->Apply(styles)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1.0);

// pelage's frame against the hand-written references of the same work (fur_limit.h: SSE, 4 hairs
// per vector; AVX, 8; AVX with 16-hair frames), alternating frame by frame in one run so all see
// the same machine state: pelage_ms, sse_ms, avx_ms and avx16_ms are their medians, limit_ms the
// fastest reference's, `ratio` =
// limit_ms / pelage_ms (1 = pelage matches the best reference; the target is >= 0.9). Every output
// is first checked to be bit-identical to pelage's. Arguments: style (0 line, 1 polyline), threads,
// hairs, preset (0 fig9, 1 default).
void BM_FurVsLimit(benchmark::State& st) {
  if (!bench::haveFurLimit()) {
    st.SkipWithError("no hand-written reference on this CPU architecture");
    return;
  }
  const auto style = static_cast<fur::HairStyle>(st.range(0));
  const int threads = static_cast<int>(st.range(1));
  setThreadCount(threads);
  const Monkey& m = monkey();
  fur::FurParams params = fur::loadFurPreset(st.range(3) == 0 ? "fig9" : "default");
  params.setHairCount(static_cast<double>(st.range(2)));
  for (auto& c : params.coats) c.style = style;
  const fur::FurRoots roots = fur::growRoots(m.skin, params);
  if (!bench::furLimitCovers(params, roots)) {
    st.SkipWithError("the reference does not cover this preset");
    return;
  }
  const skin::DeformedSkin& deformed = restSkin();
  fur::FurWorkspace ws;
  fur::FurFrame frame;
  bench::FurLimitWork limit;
  const fur::FurView view;  // culling off: every hair
  fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);
  for (int width : {4, 8, 16}) {
    bench::furLimitFrame(m.skin, roots, params, deformed, limit, width);
    for (int c = 0; c < fur::kCoatCount; ++c) {
      const auto ci = static_cast<std::size_t>(c);
      const std::size_t bytes = frame.coats[ci].positions.count * sizeof(float);
      if (std::memcmp(frame.coats[ci].positions.data(), limit.positions[ci].data(), bytes) != 0 ||
          std::memcmp(frame.coats[ci].normals.data(), limit.normals[ci].data(), bytes) != 0) {
        st.SkipWithError("a reference's hairs differ from pelage's: not the same work");
        return;
      }
    }
  }
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  std::vector<double> pelageMs, sseMs, avxMs, avx2Ms;
  for (auto _ : st) {
    const auto t0 = Clock::now();
    fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);
    const auto t1 = Clock::now();
    bench::furLimitFrame(m.skin, roots, params, deformed, limit, 4);
    const auto t2 = Clock::now();
    bench::furLimitFrame(m.skin, roots, params, deformed, limit, 8);
    const auto t3 = Clock::now();
    bench::furLimitFrame(m.skin, roots, params, deformed, limit, 16);
    const auto t4 = Clock::now();
    benchmark::ClobberMemory();
    pelageMs.push_back(ms(t0, t1));
    sseMs.push_back(ms(t1, t2));
    avxMs.push_back(ms(t2, t3));
    avx2Ms.push_back(ms(t3, t4));
  }
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double p = median(pelageMs), sse = median(sseMs), avx = median(avxMs);
  const double avxPair = median(avx2Ms);
  const double l = std::min({sse, avx, avxPair});
  const double n = static_cast<double>(frame.drawn());
  st.counters["pelage_ms"] = p;
  st.counters["sse_ms"] = sse;
  st.counters["avx_ms"] = avx;
  st.counters["avx16_ms"] = avxPair;
  st.counters["limit_ms"] = l;
  st.counters["ratio"] = l / p;
  st.counters["hairs"] = n;
  st.counters["pelage_hairs/s"] = n / (p * 1e-3);
  st.SetLabel(std::string(fur::styleName(style)) + (st.range(3) == 0 ? " fig9 " : " default ") +
              fur::activeKernelTarget());
}
BENCHMARK(BM_FurVsLimit)
    ->Args({1, 2, 500000, 0})
    ->Args({0, 2, 500000, 0})
    ->Args({1, 2, 500000, 1})
    ->Args({1, 1, 500000, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
