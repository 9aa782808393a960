// Tutorial 101: load a creature, grow its fur, play a clip and write each frame's hairs as PLY.
//
//   101_hair_ply [MODEL [CLIP [FRAMES [OUT_DIR]]]]
//
// MODEL is a glTF file (.gltf/.glb), a mesh (.obj/.ply/.off/.stl), a creature JSON, or "monkey"
// (the built-in creature, the default). CLIP is one of the model's clips by name ("" or absent: the
// first). FRAMES (default 3) frames at 30 frames per second go to OUT_DIR/hairs_NNNNN.ply
// (default: the current folder), each hair a polyline with a width and a colour per point.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "pelage/fur/colors.h"
#include "pelage/fur/hair_ply.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"
#include "pelage/scene/playback.h"

int main(int argc, char** argv) {
  using namespace pelage;
  const std::string modelSpec = argc > 1 ? argv[1] : "monkey";
  const std::string clipName = argc > 2 ? argv[2] : "";
  const std::string outDir = argc > 4 ? argv[4] : ".";
  try {
    const int frames = argc > 3 ? std::stoi(argv[3]) : 3;
    // 1. The creature: its body (segments or joints), its skin bound to them, its clips. glTF
    //    skins under 4,000 triangles are subdivided so that roots grow on a smooth surface.
    scene::Model model = scene::loadModel(modelSpec);

    // 2. The fur: a preset (the built-in "default": a dense overcoat and undercoat), here with
    //    fewer hairs so that the files stay small. growFur validates the parameters and grows the
    //    roots (barycentric points on the skin's triangles, Van Gelder & Wilhelms 1997, sec. 3.2).
    fur::FurParams params = fur::loadFurPreset("default");
    params.setHairCount(20000);
    const scene::Fur fur = scene::growFur(model, params);

    // 3. The frame loop: a Playback poses frame f (clip time f / fps), deforms the skin and
    //    recomputes every hair from its root (sec. 3.2 to 3.8) on the CPU.
    scene::PlaybackOptions options;
    options.clip = scene::resolveClip(model, clipName);  // -1: the model has no clip
    options.hairSource = scene::HairSource::Cpu;
    scene::Playback playback(model, fur, options);
    fur::FurFrame hairs;
    for (int f = 0; f < frames; ++f) {
      playback.poseFrame(f);
      playback.evaluateFur(fur::FurView{});  // every hair (no distance culling)
      playback.takeHairs(hairs);             // the frame's hair buffers, without a copy
      fur::fillHairColors(fur.colors, hairs);
      char name[32];
      std::snprintf(name, sizeof name, "/hairs_%05d.ply", f);
      const fur::HairPlyCounts counts =
          fur::writeHairPly(outDir + name, hairs, fur.params, "pelage tutorial 101", &fur.colors);
      std::printf("%s: %lld hairs, %lld points\n", (outDir + name).c_str(),
                  static_cast<long long>(hairs.drawn()), static_cast<long long>(counts.vertices));
    }
  } catch (const std::invalid_argument&) {  // std::stoi on an argument that is not a number
    std::fprintf(stderr,
                 "usage: 101_hair_ply [MODEL [CLIP [FRAMES [OUT_DIR]]]]: FRAMES is a number\n");
    return 2;
  } catch (const std::exception& e) {  // pelage reports bad input as InputError (util/error.h)
    std::fprintf(stderr, "101_hair_ply: %s\n", e.what());
    return 1;
  }
  return 0;
}
