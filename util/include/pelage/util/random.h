// Counter-based random numbers: a value depends only on (seed, stream, index), never on call order,
// so results are identical whatever the thread count or the order in which items are visited.
#pragma once

#include <cstdint>

namespace pelage {

// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
inline constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// 64 random bits for item `index` of `stream` under `seed`.
inline constexpr std::uint64_t randomBits(std::uint64_t seed, std::uint64_t stream,
                                          std::uint64_t index) {
  return mix64(mix64(seed ^ mix64(stream + 0x632be59bd9b4e019ull)) + index);
}

// Uniform float in [0, 1) with 24 random bits (exactly representable).
inline constexpr float uniform01(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return static_cast<float>(randomBits(seed, stream, index) >> 40) * (1.0f / 16777216.0f);
}

// Uniform double in [0, 1) with 53 random bits.
inline constexpr double uniform01d(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return static_cast<double>(randomBits(seed, stream, index) >> 11) * (1.0 / 9007199254740992.0);
}

// Named streams so that different uses of one seed never share random numbers.
enum RandomStream : std::uint64_t {
  kStreamBarycentricTable = 1,
  kStreamAllocation = 2,
  kStreamCulling = 3,
  kStreamHairEnd = 4,
  kStreamNormal = 5,
  kStreamCoatSplit = 6,
  kStreamColor = 7,    // per-hair colour variation
  kStreamDensity = 8,  // density-map placement of roots inside a triangle
  kStreamClump = 9,    // clump centres (the root of least priority in each cell)
  kStreamUser = 1000,
};

}  // namespace pelage
