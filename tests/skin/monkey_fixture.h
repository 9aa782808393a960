// The default monkey's skin, built once per test binary.
#pragma once

#include "pelage/scene/model.h"

namespace pelage::test {

inline const scene::Model& defaultMonkey() {
  static const scene::Model m = scene::loadModel("monkey");
  return m;
}

}  // namespace pelage::test
