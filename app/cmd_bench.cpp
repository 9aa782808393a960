// pelage bench: how fast the fur of one frame is recomputed (Van Gelder & Wilhelms 1997, sec. 4:
// "recalculating the fur from scratch" every frame): hairs per second and ms per frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

#include "commands.h"
#include "options.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/playback.h"
#include "pelage/skin/deform.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"

namespace pelage::app {

void addBenchCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bench", "Time the per-frame fur (and skin) computation: hairs/s and ms/frame");
  auto model = std::make_shared<ModelOptions>();
  auto pose = std::make_shared<PoseOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto frames = std::make_shared<int>(50);
  model->add(*cmd);
  pose->add(*cmd);
  furArgs->add(*cmd);
  cmd->add_option("--repeat", *frames,
                  "Timed frames, each the same posed frame [1, 100000] (default 50)");
  common->add(*cmd, false);
  cmd->callback([=] {
    if (*frames < 1 || *frames > 100000)
      inputError("--repeat ", *frames, " is out of range [1, 100000]");
    const fur::FurParams params = furArgs->resolve();
    scene::Model m = model->load();
    const scene::Fur fur = scene::growFur(m, params, "fur '" + params.name + "'");
    const fur::FurRoots& roots = fur.roots;
    scene::PlaybackOptions po;
    po.stillPose = pose->stillPose(m);
    po.hairSource = scene::HairSource::Cpu;
    scene::Playback playback(m, fur, po);
    playback.poseFrame(0);
    // What is timed: the skin deformation and fur::generateFur of the posed frame, every hair.
    const anatomy::BodyState body = playback.state().body;
    skin::DeformedSkin deformed = playback.state().skin;
    fur::FurWorkspace ws;
    fur::FurFrame frame;
    const fur::FurView view;  // culling off: every hair, every frame
    fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);  // sizes the buffers
    using Clock = std::chrono::steady_clock;
    std::vector<double> furMs, skinMs;
    for (int f = 0; f < *frames; ++f) {
      const auto t0 = Clock::now();
      skin::deformSkin(m.skin, body, deformed);
      const auto t1 = Clock::now();
      fur::generateFur(m.skin, roots, params, deformed, view, ws, frame);
      const auto t2 = Clock::now();
      skinMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      furMs.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    }
    std::sort(furMs.begin(), furMs.end());
    std::sort(skinMs.begin(), skinMs.end());
    const double median = furMs[furMs.size() / 2];
    const double hairs = static_cast<double>(frame.drawn());
    std::printf(
        "model %s: %d triangles, %d vertices; fur %s: %lld overcoat %s + %lld undercoat %s hairs\n",
        m.name.c_str(), m.skin.numTriangles(), m.skin.numVertices(), params.name.c_str(),
        static_cast<long long>(frame.coats[0].drawn), fur::styleName(frame.coats[0].layout.style),
        static_cast<long long>(frame.coats[1].drawn), fur::styleName(frame.coats[1].layout.style));
    std::printf("threads %d, kernel %s, %d frames\n", threadCount(),
                fur::activeKernelTarget().c_str(), *frames);
    std::printf("fur:  %.3f ms/frame median (min %.3f, max %.3f), %.1f M hairs/s\n", median,
                furMs.front(), furMs.back(), hairs / median / 1e3);
    std::printf("skin: %.3f ms/frame median (deformation and normals)\n",
                skinMs[skinMs.size() / 2]);
  });
}

}  // namespace pelage::app
