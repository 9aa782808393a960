// pelage hair: one frame of a creature's fur (Van Gelder & Wilhelms 1997 sec. 3) as a PLY file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <filesystem>

#include "commands.h"
#include "options.h"
#include "pelage/fur/culling.h"
#include "pelage/fur/generate.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/fur/roots.h"
#include "pelage/scene/dynamic_fur.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/playback.h"
#include "pelage/skin/deform.h"
#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"

namespace pelage::app {
namespace {

// Length of hair h (m): distance from its root to its end (tube: between the first and last ring
// centres).
double hairLength(const fur::HairBuffers& b, std::int64_t h) {
  const int P = b.layout.pointsPerHair();
  const int ring = b.layout.ringSides;
  Eigen::Vector3d first = Eigen::Vector3d::Zero(), last = Eigen::Vector3d::Zero();
  for (int j = 0; j < ring; ++j) {
    first += Eigen::Map<const Eigen::Vector3f>(b.positions.data() + (h * P + j) * 3).cast<double>();
    last += Eigen::Map<const Eigen::Vector3f>(b.positions.data() + (h * P + P - ring + j) * 3)
                .cast<double>();
  }
  return (last - first).norm() / ring;
}

// One line per coat: hairs, style, lengths, and how far the ends drop below the roots.
void summarise(const fur::FurFrame& frame, const fur::FurParams& params) {
  for (int c = 0; c < fur::kCoatCount; ++c) {
    const fur::HairBuffers& b = frame.coats[static_cast<std::size_t>(c)];
    if (b.drawn == 0) continue;
    double lo = 1e30, hi = 0.0, sum = 0.0, drop = 0.0;
    const Eigen::Map<const Eigen::Vector3f> up(params.up.data());
    for (std::int64_t h = 0; h < b.drawn; ++h) {
      const double L = hairLength(b, h);
      lo = std::min(lo, L);
      hi = std::max(hi, L);
      sum += L;
      const int P = b.layout.pointsPerHair();
      const Eigen::Map<const Eigen::Vector3f> root(b.positions.data() + h * P * 3);
      const Eigen::Map<const Eigen::Vector3f> end(b.positions.data() + (h * P + P - 1) * 3);
      drop += static_cast<double>((end - root).dot(up));
    }
    const double meanRise = drop / static_cast<double>(b.drawn) * 1e3;
    std::printf(
        "%s: %lld %s hairs, %d points each; length %.2f to %.2f mm (mean %.2f); ends %.2f mm %s "
        "their roots on average\n",
        c == 0 ? "overcoat" : "undercoat", static_cast<long long>(b.drawn),
        fur::styleName(b.layout.style), b.layout.pointsPerHair(), lo * 1e3, hi * 1e3,
        sum / static_cast<double>(b.drawn) * 1e3, std::abs(meanRise),
        meanRise < 0.0 ? "below" : "above");
  }
}

}  // namespace

void addHairCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "hair",
      "Write one frame of a creature's hairs as PLY (points, normals, edges or tube faces)");
  auto model = std::make_shared<ModelOptions>();
  auto pose = std::make_shared<PoseOptions>();
  auto furArgs = std::make_shared<FurOptions>();
  auto dynamics = std::make_shared<DynamicsOptions>();
  auto frames = std::make_shared<FrameOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto out = std::make_shared<std::string>();
  auto distance = std::make_shared<double>(0.0);
  auto distanceOpt = cmd->add_option(
      "--distance", *distance,
      "Viewing distance (m) for distance culling (sec. 3.3) [0, 10000]; without it every "
      "hair is written");
  model->add(*cmd);
  pose->add(*cmd);
  furArgs->add(*cmd);
  dynamics->add(*cmd, true);
  frames->addFps(*cmd);
  cmd->add_option("--out", *out, "Output .ply file");
  auto printPreset = std::make_shared<bool>(false);
  cmd->add_flag("--print-preset", *printPreset,
                "Print the fur's preset with every field resolved (its base, the default preset "
                "and the options applied) as JSON, and write nothing");
  common->add(*cmd, true);
  cmd->callback([=] {
    if (*printPreset) {
      std::fputs(fur::furPresetJson(furArgs->resolve()).c_str(), stdout);
      return;
    }
    if (out->empty()) inputError("--out is required (or --print-preset)");
    if (distanceOpt->count() > 0 && !(*distance >= 0.0 && *distance <= 1e4))
      inputError("--distance ", *distance, " is out of range [0, 10000] (metres)");
    frames->validateFps();
    if (lowerExtension(*out) != ".ply")
      inputError("--out ", *out, ": hairs are written as binary PLY; the file must end in .ply");
    // The output folder as `render` and `export` make theirs: created when missing (and removed
    // again if the run fails).
    const std::string folder = std::filesystem::path(*out).parent_path().string();
    const NewFolders folders(folder.empty() ? "." : folder);
    if (!folder.empty()) ensureWritableDirectory(folder);
    // Options first: bad values fail before the model is built.
    const fur::FurParams params = furArgs->resolve();
    const fur::DynamicsParams dyn = dynamics->resolve();
    const bool quiet = common->quiet;
    scene::Model m = model->load();
    const scene::Fur fur = scene::growFur(m, params, "fur '" + params.name + "'");
    const fur::FurRoots& roots = fur.roots;
    fur::FurView view;
    if (distanceOpt->count() > 0) {
      view.culling = params.culling.enabled;
      view.viewDistance = static_cast<float>(*distance);
      view.referenceDistance = fur::referenceDistance(params);
      // Seen by the reference camera (its field of view and image height) from --distance.
      view.fovYDegrees = view.referenceFovYDegrees = params.culling.fovYDegrees;
      view.imageHeight = view.referenceHeight = params.culling.referenceHeight;
    }
    // One frame played by the frame owner: the pose (or, with fur dynamics, the clip's frames from
    // its start up to --time: scene/playback.h), then its hairs.
    scene::PlaybackOptions po;
    po.hairSource = scene::HairSource::Cpu;
    int shown = 0;
    if (dynamics->enabled()) {
      if (pose->clip.empty())
        inputError(
            "--dynamics on needs --clip naming one of the model's clips (see `pelage info`)");
      po.clip = scene::resolveClip(m, pose->clip);
      po.clock.fps = frames->fps;
      po.clock.preRollFrames = dynamics->preRoll;
      po.dynamics = true;
      po.dynamicsParams = dyn;
      shown = scene::oneFrameAt(po, pose->time);
    } else {
      po.stillPose = pose->stillPose(m);
    }
    scene::Playback playback(m, fur, po);
    playback.poseFrame(shown);
    playback.evaluateFur(view);
    const fur::FurFrame& frame = playback.state().fur;
    const std::string comment =
        str("model ", m.name, ", fur ", params.name, ", seed ", params.seed, ", ", frame.drawn(),
            " of ", roots.total(), " hairs (culling factor ", frame.cullingFactor, ")");
    const fur::HairPlyCounts n = fur::writeHairPly(*out, frame, params, comment, &fur.colors);
    if (quiet) return;
    if (dynamics->enabled()) {
      std::printf(
          "dynamic fur: frame %d of clip %s at %g fps (time %.4f s), simulated from frame %d\n",
          shown, m.clips[static_cast<std::size_t>(po.clip)].name.c_str(), frames->fps,
          po.clock.secondsAt(shown), scene::preRollStart(shown, po.clock));
    }
    std::printf("%s: %s on %s (%d triangles, %.4f m^2 furred)\n", out->c_str(), params.name.c_str(),
                m.name.c_str(), m.skin.numTriangles(), roots.furredArea);
    if (view.culling)
      std::printf(
          "distance %.3f m, reference %.3f m: culling factor %.3f, %lld of %lld hairs drawn\n",
          static_cast<double>(view.viewDistance), static_cast<double>(view.referenceDistance),
          static_cast<double>(frame.cullingFactor), static_cast<long long>(frame.drawn()),
          static_cast<long long>(roots.total()));
    summarise(frame, params);
    printCoverage(
        fur::estimateCoverage(m.skin, fur.params, fur.roots.lengths(m.skin), &fur.groom.vertex));
    std::printf("wrote %lld vertices, %lld edges, %lld faces\n", static_cast<long long>(n.vertices),
                static_cast<long long>(n.edges), static_cast<long long>(n.faces));
  });
}

}  // namespace pelage::app
