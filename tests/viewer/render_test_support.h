// The test critter with a clip (tail wag, head nod, body moving forward 0.2 m/s) and its fur, for
// the frame-sequence tests.
#pragma once

#include <string>

#include "pelage/animation/clip_file.h"
#include "pelage/fur/preset.h"
#include "pelage/scene/frame.h"
#include "viewer/gl_fixture.h"

namespace pelage::test {

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
    scene::Model c = testCritter();
    c.clips.clear();
    c.clips.push_back(animation::parseClip(c.body, kWagClip, "wag clip"));
    return c;
  }();
  return m;
}

inline const scene::Fur& wagFur() {
  static const scene::Fur f = [] {
    fur::FurParams p = fur::loadFurPreset("default");
    p.hairs = 4000;
    return scene::growFur(wagCritter(), p, "test");
  }();
  return f;
}

}  // namespace pelage::test
