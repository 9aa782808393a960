// Fur dynamics (issue 7) against the paper's quasi-static fur on the default monkey (130k
// triangles): fig9 preset, 500,000 hairs, both coats polyline, culling off, the skin alternating
// between two poses of the walk so that the hairs move. Target: a dynamic frame (spring step +
// hairs, one fused pass) costs at most 2x a quasi-static one. Also the state step alone (pre-roll).
// Arguments: mode (0 quasi-static, 1 dynamic, 2 dynamic step only), threads, hairs.
#include <benchmark/benchmark.h>

#include <string>

#include "pelage/anatomy/creature.h"
#include "pelage/anatomy/pose.h"
#include "pelage/animation/procedural.h"
#include "pelage/fur/dynamics.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/models/builtin.h"
#include "pelage/skin/build_from_shapes.h"
#include "pelage/skin/deform.h"
#include "pelage/util/parallel.h"

namespace {

using namespace pelage;

struct Monkey {
  anatomy::Creature creature;
  skin::SkinMesh skin;
  skin::DeformedSkin poses[2];  // walk at 0.0 s and 0.1 s
};
const Monkey& monkey() {
  static const Monkey m = [] {
    Monkey out;
    out.creature =
        anatomy::parseCreature(std::string(*models::builtinFile("monkey.json")), "built-in monkey");
    out.skin = skin::buildSkin(out.creature, {out.creature.defaultTriangles});
    for (int k = 0; k < 2; ++k) {
      anatomy::Pose pose;
      animation::evaluateMonkeyClip(out.creature, "walk", 0.1 * k, pose);
      anatomy::BodyState state;
      anatomy::forwardKinematics(out.creature.body, pose, state);
      skin::deformSkin(out.skin, state, out.poses[k]);
    }
    return out;
  }();
  return m;
}

void BM_DynamicsFrame(benchmark::State& st) {
  const int mode = static_cast<int>(st.range(0));
  const int threads = static_cast<int>(st.range(1));
  setThreadCount(threads);
  const Monkey& m = monkey();
  fur::FurParams params = fur::loadFurPreset("fig9");
  params.setHairCount(static_cast<double>(st.range(2)));
  for (auto& c : params.coats) c.style = fur::HairStyle::Polyline;
  const fur::FurRoots roots = fur::growRoots(m.skin, params);
  const fur::DynamicsParams dynamics;
  fur::FurDynamicsState state;
  fur::resetFurDynamics(roots, state);
  fur::FurWorkspace ws;
  fur::FurFrame frame;
  const fur::FurView view;  // culling off
  const double dt = 1.0 / 30.0;
  auto run = [&](int k) {
    const skin::DeformedSkin& d = m.poses[k & 1];
    if (mode == 0)
      fur::generateFur(m.skin, roots, params, d, view, ws, frame);
    else if (mode == 1)
      fur::generateDynamicFur(m.skin, roots, params, dynamics, d, dt, view, state, ws, frame);
    else
      fur::stepFurDynamics(m.skin, roots, params, dynamics, d, dt, state, ws);
  };
  for (int k = 0; k < 3; ++k) run(k);  // sizes the buffers, starts the springs
  int k = 0;
  for (auto _ : st) {
    run(k++);
    benchmark::DoNotOptimize(frame.coats[0].positions.data());
    benchmark::DoNotOptimize(state.coats[0].data());
    benchmark::ClobberMemory();
  }
  const double n = static_cast<double>(roots.total());
  st.counters["hairs"] = n;
  st.counters["threads"] = threads;
  st.counters["hairs/s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
  static const char* names[] = {"quasi-static", "dynamic", "dynamic step only"};
  st.SetLabel(std::string(names[mode]) + " polyline " + fur::activeKernelTarget());
}

void modes(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2})
    for (int mode : {0, 1, 2}) b->Args({mode, threads, 500000});
}
BENCHMARK(BM_DynamicsFrame)
    ->Apply(modes)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
