// `pelage view --headless --benchmark`: end-to-end frame time of the viewer's frame (clip sampling,
// skinning on the CPU, skin upload, GPU fur, shading, glFinish) for several hair counts, the
// creature animated (its first clip, or a turntable) so every frame's skin and hairs differ, every
// hair drawn (no culling), both coats polylines. The NVIDIA runs of issue 5 are the defaults:
//   pelage view --benchmark     (the monkey, 500k, 1M and 5M hairs, 1920x1080, MSAA off and 4x)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>
#include <vector>

#include "pelage/render/gl_context.h"
#include "pelage/render/gl_debug.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "viewer_session.h"

namespace pelage::viewer::detail {

int runBenchmark(const ViewerOptions& options, const scene::Model& model) {
  render::ContextOptions co;
  co.debug = options.debugGl;
  auto context = render::createHeadlessContext(co);
  std::unique_ptr<render::GlDebugLog> log;
  if (options.debugGl) log = std::make_unique<render::GlDebugLog>();
  const render::ContextInfo& info = context->info();
  std::printf(
      "viewer benchmark: %s | %s | %s | %dx%d | %d CPU threads | hairs on the %s | model "
      "%s\n",
      info.renderer.c_str(), info.version.c_str(), info.backend.c_str(), options.width,
      options.height, threadCount(),
      options.dynamics                               ? "CPU (dynamic fur)"
      : options.hairSource == scene::HairSource::Cpu ? "CPU"
                                                     : "GPU",
      model.name.c_str());
  // MSAA off is the setting of the reference figures (../shared/docs/headless-gl.md); on a GPU 4x
  // is measured too, as the viewer uses it there. A software rasteriser only without (4x costs
  // ~2.3x).
  std::vector<int> sampleCounts;
  if (options.samples >= 0)
    sampleCounts = {options.samples};
  else if (info.software)
    sampleCounts = {0};
  else
    sampleCounts = {0, 4};
  std::printf("%12s %6s %12s %12s %14s %12s\n", "hairs", "MSAA", "drawn", "ms/frame", "M hairs/s",
              "min ms");
  for (const double hairs : options.benchmarkHairs) {
    ViewerOptions o = options;
    o.fur.setHairCount(hairs);
    o.noCulling = true;  // every hair drawn: the count is what is measured
    o.hairSource = options.hairSource;
    for (const int samples : sampleCounts) {
      o.samples = samples;
      ViewerSession session(o, model);
      for (fur::CoatParams& c : session.edit.coats) c.style = fur::HairStyle::Polyline;
      // Under animation: the model's first clip plays; a model without clips turns on a turntable.
      if (session.clip() < 0) session.turntableDegPerSecond = 20.0f;
      const double dt = 1.0 / 30.0;
      for (int i = 0; i < 3; ++i) {  // warm up: shader compilation, first uploads, buffer sizing
        session.frame(dt, o.width, o.height);
        session.renderer().finish();
      }
      std::vector<double> ms;
      for (int i = 0; i < options.benchmarkFrames; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        session.frame(dt, o.width, o.height);
        session.renderer().finish();
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
      }
      double mean = 0.0;
      for (double v : ms) mean += v;
      mean /= static_cast<double>(ms.size());
      const double best = *std::min_element(ms.begin(), ms.end());
      const auto drawn = static_cast<double>(session.hairsDrawn());
      std::printf("%12.0f %6d %12.0f %12.2f %14.1f %12.2f\n", hairs, session.renderer().samples(),
                  drawn, mean, drawn / mean * 1e-3, best);
      std::fflush(stdout);
    }
  }
  if (log) {
    const std::string errors = log->errors();
    PELAGE_CHECK(errors.empty(), "OpenGL reported errors:\n", errors);
  }
  return 0;
}

}  // namespace pelage::viewer::detail
