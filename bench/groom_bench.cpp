// Brushing (issue 28) on the monkey with the default preset: what one cursor move costs the viewer.
// A stroke's point re-applies the stroke so far to the groom (GroomEditor::addPoint, on the calling
// thread), then the fur regrows on the new groom (scene::growFur, on the viewer's worker thread
// while the old fur keeps drawing): the latency before the fur shows the brush. Counters: vertices
// per second for the brush, hairs per second for the regrowth.
#include <benchmark/benchmark.h>

#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/groom_editor.h"
#include "pelage/scene/model.h"

namespace {

using namespace pelage;

const scene::Model& monkey() {
  static const scene::Model m = scene::loadModel("monkey");
  return m;
}

fur::GroomStroke brushOf(fur::BrushTool tool, float strength, float radius) {
  fur::GroomStroke s;
  s.tool = tool;
  s.strength = strength;
  s.radius = radius;
  return s;
}

// A length stroke of 40 points across the monkey's rest skin, radius 3 cm: each iteration adds
// the next point (wrapping to a new stroke).
void BM_BrushPoint(benchmark::State& st) {
  const scene::Model& m = monkey();
  scene::GroomEditor e(m, scene::startingGroom(m, fur::loadFurPreset("default"), "bench"));
  const fur::GroomStroke brush = brushOf(fur::BrushTool::Length, 1.2f, 0.03f);
  const float* rest = m.skin.restPositions();
  const int nv = m.skin.numVertices();
  int k = 0;
  for (auto _ : st) {
    if (k % 40 == 0) {
      st.PauseTiming();
      e.endStroke();
      if (e.canUndo()) e.undo();
      e.beginStroke(brush);
      st.ResumeTiming();
    }
    const int v = static_cast<int>((static_cast<long long>(k % 40) * nv) / 40);
    e.addPoint(Eigen::Map<const Eigen::Vector3f>(rest + 3 * v));
    ++k;
  }
  st.counters["vertices/s"] =
      benchmark::Counter(static_cast<double>(st.iterations()) * nv, benchmark::Counter::kIsRate);
}

// The fur regrown on a brushed groom, at the preset's hair count.
void BM_RegrowGroomedFur(benchmark::State& st) {
  const scene::Model& m = monkey();
  const fur::FurParams p = fur::loadFurPreset("default");
  scene::GroomEditor e(m, scene::startingGroom(m, p, "bench"));
  e.beginStroke(brushOf(fur::BrushTool::Density, 2.0f, 0.05f));
  e.addPoint(Eigen::Map<const Eigen::Vector3f>(m.skin.restPositions()));
  e.endStroke();
  double hairs = 0.0;
  for (auto _ : st) {
    const scene::Fur f = scene::growFur(m, p, e.groom(), "bench");
    hairs += static_cast<double>(f.roots.total());
    benchmark::DoNotOptimize(f.roots.total());
  }
  st.counters["hairs/s"] = benchmark::Counter(hairs, benchmark::Counter::kIsRate);
  st.counters["hairs"] = hairs / static_cast<double>(st.iterations());
}

BENCHMARK(BM_BrushPoint)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RegrowGroomedFur)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
