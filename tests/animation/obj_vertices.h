// Vertex positions of an OBJ written by `pelage skin` (the CLI tests of tests/animation).
#pragma once

#include <Eigen/Core>

#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace pelage::test {

inline std::vector<Eigen::Vector3f> objVertices(const std::string& path) {
  std::istringstream in(readText(path));
  std::vector<Eigen::Vector3f> v;
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("v ", 0) == 0) {
      std::istringstream l(line.substr(2));
      Eigen::Vector3f p;
      l >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    }
  return v;
}

}  // namespace pelage::test
