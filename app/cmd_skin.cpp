#include <cstdio>
#include <memory>

#include "commands.h"
#include "pelage/anatomy/pose.h"
#include "pelage/skin/deform.h"
#include "pelage/skin/mesh_io.h"

namespace pelage::app {

void addSkinCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("skin", "Write the (posed) skin of a creature as OBJ or PLY");
  auto args = std::make_shared<ModelArgs>();
  auto poseArgs = std::make_shared<PoseArgs>();
  auto out = std::make_shared<std::string>();
  args->add(*cmd);
  poseArgs->add(*cmd);
  cmd->add_option("--out", *out, "Output file (.obj or .ply)")->required();
  cmd->callback([args, poseArgs, out] {
    scene::Model m = args->load();
    const anatomy::Pose pose = poseArgs->resolve(m);
    anatomy::BodyState state;
    anatomy::forwardKinematics(m.body, pose, state);
    skin::DeformedSkin deformed;
    skin::deformSkin(m.skin, state, deformed);
    skin::writeSkin(*out, m.skin, deformed.positions, deformed.normals);
    std::printf("wrote %s (%d vertices, %d triangles)\n", out->c_str(), m.skin.numVertices(),
                m.skin.numTriangles());
  });
}

}  // namespace pelage::app
