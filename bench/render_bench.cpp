// Headless export (issue 6): the cost of one exported frame of the monkey's walk at 1920x1080 with
// N polyline hairs (both coats, culling off, GPU hair source), in three parts: rendering it through
// the sequence renderer (pose, skin, GPU fur, draw, read back), encoding the PNG, and, for
// `pelage export --format ply`, computing the frame's hairs on the CPU and writing the PLY file.
// Needs OpenGL through EGL (Mesa llvmpipe or a GPU driver). Counters: hairs/s; ms/frame is the
// benchmark's time. `pelage render` overlaps encoding with rendering on worker threads, so its
// frames/s is bounded by max(render, encode / encoder threads), not their sum.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/render/gl_context.h"
#include "pelage/render/image.h"
#include "pelage/render/render_sequence.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"
#include "pelage/util/parallel.h"

namespace {

using namespace pelage;

const scene::Model& monkey() {
  static const scene::Model m = scene::loadModel("monkey");
  return m;
}

scene::Fur polylineFur(double hairs) {
  fur::FurParams p = fur::loadFurPreset("default");
  p.setHairCount(hairs);
  p.densityPerM2 = 0.0;
  p.culling.enabled = false;
  for (fur::CoatParams& c : p.coats) c.style = fur::HairStyle::Polyline;
  return scene::growFur(monkey(), p);
}

render::GlContext& context() {
  static std::unique_ptr<render::GlContext> c = render::createHeadlessContext();
  return *c;
}

render::SequenceOptions options() {
  render::SequenceOptions o;
  o.playback.clip = monkey().findClip("walk");
  o.frames = {0, 1000};
  o.width = 1920;
  o.height = 1080;
  o.samples = -1;  // as `pelage render`: 4 on a GPU, 0 on a software rasteriser
  o.outDir = std::filesystem::temp_directory_path().string();
  return o;
}

// Arguments: hairs.
void BM_RenderFrame(benchmark::State& st) {
  context();
  const scene::Fur fur = polylineFur(static_cast<double>(st.range(0)));
  render::SequenceRenderer renderer(monkey(), fur, options());
  render::Image img;
  int frame = 0;
  std::int64_t drawn = 0;
  for (auto _ : st) drawn = renderer.render(frame++ % 60, img).hairsDrawn;
  st.counters["hairs/s"] =
      benchmark::Counter(static_cast<double>(drawn), benchmark::Counter::kIsIterationInvariantRate);
  st.SetLabel(context().info().renderer);
}

void BM_EncodePng(benchmark::State& st) {
  context();
  const scene::Fur fur = polylineFur(500000.0);
  render::SequenceRenderer renderer(monkey(), fur, options());
  render::Image img;
  renderer.render(30, img);
  std::size_t bytes = 0;
  for (auto _ : st) bytes = render::encodePng(img).size();
  st.counters["PNG MB"] = static_cast<double>(bytes) / 1e6;
}

// Arguments: hairs.
void BM_ExportPlyFrame(benchmark::State& st) {
  const scene::Model& m = monkey();
  const scene::Fur fur = polylineFur(static_cast<double>(st.range(0)));
  const int clip = m.findClip("walk");
  const std::string path =
      (std::filesystem::temp_directory_path() / "pelage_bench_frame.ply").string();
  scene::FrameState state;
  int frame = 0;
  for (auto _ : st) {
    scene::evaluateClipFrame(m, clip, (frame++ % 60) / 30.0, state);
    scene::evaluateFur(m, fur, fur::FurView{}, true, state);
    fur::writeHairPly(path, state.fur, fur.params);
  }
  std::remove(path.c_str());
  st.counters["hairs/s"] = benchmark::Counter(static_cast<double>(fur.roots.total()),
                                              benchmark::Counter::kIsIterationInvariantRate);
  st.SetLabel(std::to_string(threadCount()) + " threads");
}

BENCHMARK(BM_RenderFrame)->Arg(100000)->Arg(500000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_EncodePng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ExportPlyFrame)->Arg(500000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
