// `pelage skin`: the (posed) skin of a creature as OBJ or PLY.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "options.h"
#include "pelage/scene/playback.h"
#include "pelage/skin/mesh_io.h"

namespace pelage::app {

void addSkinCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("skin", "Write the (posed) skin of a creature as OBJ or PLY");
  auto model = std::make_shared<ModelOptions>();
  auto pose = std::make_shared<PoseOptions>();
  auto common = std::make_shared<CommonOptions>();
  auto out = std::make_shared<std::string>();
  model->add(*cmd);
  pose->add(*cmd);
  cmd->add_option("--out", *out, "Output file (.obj or .ply)")->required();
  common->add(*cmd, true);
  cmd->callback([model, pose, common, out] {
    scene::Model m = model->load();
    scene::PlaybackOptions po;
    po.stillPose = pose->stillPose(m);
    const scene::Fur none;  // the skin only
    scene::Playback playback(m, none, po);
    playback.poseFrame(0);
    const scene::FrameState& state = playback.state();
    skin::writeSkin(*out, m.skin, state.skin.positions, state.skin.normals);
    if (!common->quiet)
      std::printf("wrote %s (%d vertices, %d triangles)\n", out->c_str(), m.skin.numVertices(),
                  m.skin.numTriangles());
  });
}

}  // namespace pelage::app
