// The test creatures of every suite (GL or not), each loaded once per test binary (like
// geometry-central's load_test_meshes.h): the test critter (support/critter.json: body, head facing
// +X with a "face" region, tail; 40,000 triangles, built in a fraction of the monkey's time, also
// under the sanitizers) and its fur; the critter with a clip (tail wag, head nod, body moving
// forward 0.2 m/s) and its fur; the built-in monkey; and the creatures by name (the monkey and the
// shared glTF models).
#pragma once

#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "pelage/animation/clip_file.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "pelage/scene/model.h"
#include "support/files.h"

namespace pelage::test {

// "monkey" (built in), or a shared model by its folder name (NAME/NAME.glb or .gltf under
// ../shared/models), loaded on first use and kept; null when the shared file is absent.
inline const scene::Model* creature(const std::string& name) {
  static std::map<std::string, std::optional<scene::Model>> loaded;
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = loaded.find(name);
  if (it == loaded.end()) {
    std::optional<scene::Model> m;
    if (name == "monkey") {
      m = scene::loadModel("monkey");
    } else {
      const std::string dir = std::string(PELAGE_SHARED_MODELS_DIR) + "/" + name + "/";
      std::string file = dir + name + ".glb";
      if (!std::filesystem::exists(file)) file = dir + name + ".gltf";
      if (std::filesystem::exists(file)) m = scene::loadModel(file);
    }
    it = loaded.emplace(name, std::move(m)).first;
  }
  return it->second ? &*it->second : nullptr;
}

// The built-in monkey (~130k triangles).
inline const scene::Model& defaultMonkey() {
  return *creature("monkey");
}

inline const scene::Model& sceneCritter() {
  static const scene::Model m = scene::loadModel(PELAGE_TEST_CRITTER);
  return m;
}

inline const scene::Fur& sceneFur() {
  static const scene::Fur f = [] {
    fur::FurParams p = fur::loadFurPreset("default");
    p.setHairCount(40000);
    return scene::growFur(sceneCritter(), p, "test");
  }();
  return f;
}

inline const char* kWagClip = R"({ "name": "wag", "duration": 1.0, "channels": [
  { "segment": "tail", "path": "rotate", "interpolation": "cubic", "keys": [
    { "time": 0, "axis": [0, 0, 1], "degrees": -30 }, { "time": 0.5, "axis": [0, 0, 1], "degrees": 30 },
    { "time": 1, "axis": [0, 0, 1], "degrees": -30 } ] },
  { "segment": "head", "path": "rotate", "keys": [
    { "time": 0, "axis": [0, 1, 0], "degrees": 0 }, { "time": 0.5, "axis": [0, 1, 0], "degrees": 20 },
    { "time": 1, "axis": [0, 1, 0], "degrees": 0 } ] },
  { "segment": "body", "path": "translate", "keys": [
    { "time": 0, "value": [0, 0, 0] }, { "time": 1, "value": [0.2, 0, 0] } ] } ] })";

// The critter with the "wag" clip as clip 0.
inline const scene::Model& wagCritter() {
  static const scene::Model m = [] {
    scene::Model c = sceneCritter();
    c.clips.clear();
    c.clips.push_back(animation::parseClip(c.body, kWagClip, "wag clip"));
    return c;
  }();
  return m;
}

inline const scene::Fur& wagFur() {
  static const scene::Fur f = [] {
    fur::FurParams p = fur::loadFurPreset("default");
    p.setHairCount(4000);
    return scene::growFur(wagCritter(), p, "test");
  }();
  return f;
}

}  // namespace pelage::test
