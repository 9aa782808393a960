// A per-coat vertex value at a root (private to fur/): the groom's per-vertex pairs (overcoat,
// undercoat) interpolated as sec. 3.2 interpolates at the root with barycentric b on the
// triangle of vertices v, in the form s1 + b2 (s2 - s1) + b3 (s3 - s1): exactly s where the three
// vertices agree, so a hair there grows (and is coloured) as in a coat of that value.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pelage::fur::detail {

inline float coatValueAtRoot(const std::vector<Eigen::Vector2f>& values, const std::int32_t* v,
                             const float* b, int coat) {
  const auto at = [&](int i) { return values[static_cast<std::size_t>(v[i])][coat]; };
  return at(0) + b[1] * (at(1) - at(0)) + b[2] * (at(2) - at(0));
}

}  // namespace pelage::fur::detail
