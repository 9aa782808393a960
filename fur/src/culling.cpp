#include "pelage/fur/culling.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "pelage/util/error.h"
#include "pelage/util/parallel.h"
#include "pelage/util/random.h"

namespace pelage::fur {

namespace {
double tanHalf(float fovYDegrees) {
  return std::tan(0.5 * static_cast<double>(fovYDegrees) * 3.14159265358979323846 / 180.0);
}
}  // namespace

float pixelsPerMeter(float distance, float fovYDegrees, int imageHeight) {
  return static_cast<float>(static_cast<double>(imageHeight) /
                            (2.0 * static_cast<double>(distance) * tanHalf(fovYDegrees)));
}

// Van Gelder & Wilhelms 1997, sec. 3.3: the zoom factor c, as the ratio of the reference's scale on
// screen to the camera's (see the file comment).
float cullingFactor(const FurView& view) {
  if (!view.culling || !(view.referenceDistance > 0.0f) || view.imageHeight <= 0) return 1.0f;
  const double c = static_cast<double>(view.viewDistance) /
                   static_cast<double>(view.referenceDistance) *
                   (tanHalf(view.fovYDegrees) / tanHalf(view.referenceFovYDegrees)) *
                   (static_cast<double>(view.referenceHeight) / view.imageHeight);
  return c > 1.0 ? static_cast<float>(c) : 1.0f;
}

float defaultReferenceDistance(const FurParams& params) {
  const double d =
      1e-3 * static_cast<double>(params.coats[kOvercoat].width.rootMm) *
      static_cast<double>(params.culling.referenceHeight) /
      (2.0 * tanHalf(params.culling.fovYDegrees) * static_cast<double>(kReferenceRootPixels));
  return d > 1e-6 ? static_cast<float>(d) : 1e-6f;
}

float referenceDistance(const FurParams& params) {
  return params.culling.referenceDistance > 0.0f ? params.culling.referenceDistance
                                                 : defaultReferenceDistance(params);
}

Eigen::Vector3f creatureCenter(const skin::DeformedSkin& deformed) {
  if (deformed.positions.empty()) return Eigen::Vector3f::Zero();
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : deformed.positions) box.extend(p);
  return box.center();
}

FurView makeFurView(const FurParams& params, const skin::DeformedSkin& deformed,
                    const ViewCamera& camera) {
  FurView v;
  v.culling = params.culling.enabled;
  v.referenceDistance = referenceDistance(params);
  v.viewDistance = (camera.eye - creatureCenter(deformed)).norm();
  v.fovYDegrees = camera.fovYDegrees;
  v.referenceFovYDegrees = params.culling.fovYDegrees;
  v.imageHeight = camera.imageHeight;
  v.referenceHeight = params.culling.referenceHeight;
  return v;
}

std::int64_t computeDrawnStart(const CoatRoots& roots, std::uint64_t coatSeedValue, float factor,
                               std::vector<std::int32_t>& drawnStart) {
  const auto& start = roots.triangleStart;
  PELAGE_CHECK(!start.empty(), "roots without triangleStart");
  const std::int64_t nT = static_cast<std::int64_t>(start.size()) - 1;
  if (drawnStart.size() != start.size()) drawnStart.resize(start.size());
  // Two passes over fixed chunks (no allocation): drawn counts and chunk sums, then offsets.
  constexpr std::int64_t kChunks = 64;
  const std::int64_t per = (nT + kChunks - 1) / kChunks;
  std::array<std::int64_t, kChunks + 1> chunkSum{};
  parallelFor(kChunks, 1, [&](std::int64_t c) {
    const std::int64_t b = c * per, e = std::min(nT, b + per);
    std::int64_t sum = 0;
    for (std::int64_t t = b; t < e; ++t) {
      const std::int32_t k =
          start[static_cast<std::size_t>(t) + 1] - start[static_cast<std::size_t>(t)];
      std::int32_t kd = 0;
      if (k > 0) {
        // Van Gelder & Wilhelms 1997, sec. 3.3: the reduced allocation k / c, random rounding
        // floor(k / c + u) so small triangles are not all rounded down to zero.
        const float u = uniform01(coatSeedValue, kStreamCulling, static_cast<std::uint64_t>(t));
        const auto f = static_cast<std::int32_t>(std::floor(static_cast<float>(k) / factor + u));
        kd = std::min(k, f);
      }
      drawnStart[static_cast<std::size_t>(t) + 1] = kd;
      sum += kd;
    }
    chunkSum[static_cast<std::size_t>(c) + 1] = sum;
  });
  for (std::size_t c = 1; c <= kChunks; ++c) chunkSum[c] += chunkSum[c - 1];
  drawnStart[0] = 0;
  parallelFor(kChunks, 1, [&](std::int64_t c) {
    const std::int64_t b = c * per, e = std::min(nT, b + per);
    std::int64_t run = chunkSum[static_cast<std::size_t>(c)];
    for (std::int64_t t = b; t < e; ++t) {
      run += drawnStart[static_cast<std::size_t>(t) + 1];
      drawnStart[static_cast<std::size_t>(t) + 1] = static_cast<std::int32_t>(run);
    }
  });
  return chunkSum[kChunks];
}

}  // namespace pelage::fur
