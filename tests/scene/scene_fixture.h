// The test critter (tests/scene/critter.json: body, head facing +X with a "face" region, tail;
// 40,000 triangles, built in a fraction of the monkey's time, also under the sanitizers) and its
// fur, built once per test binary.
#pragma once

#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"

namespace pelage::test {

inline const scene::Model& sceneCritter() {
  static const scene::Model m = scene::loadModel(PELAGE_SOURCE_DIR "/tests/scene/critter.json");
  return m;
}

inline const scene::Fur& sceneFur() {
  static const scene::Fur f = [] {
    fur::FurParams p = fur::loadFurPreset("default");
    p.hairs = 40000;
    return scene::growFur(sceneCritter(), p, "test");
  }();
  return f;
}

}  // namespace pelage::test
