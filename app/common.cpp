#include "commands.h"

#include <cmath>
#include <filesystem>

#include "pelage/anatomy/pose_file.h"
#include "pelage/animation/clip.h"
#include "pelage/animation/clip_file.h"
#include "pelage/util/error.h"

namespace pelage::app {

void ModelArgs::add(CLI::App& cmd) {
  cmd.add_option(
      "model", model,
      "Creature: 'monkey' (built-in, default), a creature .json, a .gltf/.glb, or a static "
      ".obj/.ply/.off/.stl mesh");
  cmd.add_option("--triangles", triangles,
                 "Skin triangles for creatures built from shapes [2000, 2000000] (default: the "
                 "creature's, 130000 for the monkey)");
  cmd.add_option("--unit-scale", unitScale,
                 "glTF: metres per file unit, (0, 1e6] (default: detected from the bounding box)");
  cmd.add_option(
      "--no-fur", noFur,
      "glTF: regions (material or node names, '*' wildcards) that grow no fur (default: Eye*, "
      "Hooves, Nose, *Horn*, ...)");
  cmd.add_option(
      "--directions", directions,
      "glTF: JSON side file of per-joint segment directions (default: <model>.directions.json "
      "if it exists)");
}

scene::Model ModelArgs::load() const {
  scene::LoadOptions opt;
  opt.triangles = triangles;
  if (unitScale != 0.0 && !(unitScale > 0.0 && unitScale <= 1e6))
    inputError("--unit-scale ", unitScale, " is out of range (0, 1000000] metres per file unit");
  opt.unitScale = static_cast<float>(unitScale);
  if (!noFur.empty()) opt.noFurRegions = noFur;
  opt.segmentDirections = directions;
  return scene::loadModel(model, opt);
}

void PoseArgs::add(CLI::App& cmd) {
  cmd.add_option("--pose", posePath, "Pose file (JSON) bending segments from the rest pose");
  cmd.add_option(
      "--clip", clip,
      "Pose from this clip: one of the model's (see `pelage info`) or a clip .json file");
  timeOpt = cmd.add_option("--time", time,
                           "Time in the clip, seconds [0, 1000000] (default 0; loops wrap)");
}

anatomy::Pose PoseArgs::resolve(scene::Model& model) const {
  if (clip.empty()) {
    if (timeOpt && timeOpt->count() > 0) inputError("--time needs --clip");
    return posePath.empty() ? anatomy::restPose(model.body)
                            : anatomy::loadPose(model.body, posePath);
  }
  if (!posePath.empty()) inputError("--pose and --clip cannot be used together");
  if (!(time >= 0.0 && time <= 1e6))
    inputError("--time ", time, " is out of range [0, 1000000] seconds");
  anatomy::Pose pose;
  const int c = scene::resolveClip(model, clip);
  animation::sampleClip(model.clips[static_cast<std::size_t>(c)], model.body, time, pose);
  return pose;
}

}  // namespace pelage::app
