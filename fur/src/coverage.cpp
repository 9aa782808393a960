#include "pelage/fur/coverage.h"

#include <algorithm>
#include <cmath>

#include "pelage/fur/roots.h"

namespace pelage::fur {
namespace {

// The furred area (m^2) and the area-weighted mean of the vertex fur length over it (m): a
// triangle's mean of the linear interpolation of its vertex lengths is the mean of the three.
struct SkinFur {
  double area = 0.0, meanLength = 0.0;
};

SkinFur skinFur(const skin::SkinMesh& skin, const float* lengths) {
  const std::vector<double> area = triangleAreas(skin);
  const float* len = lengths ? lengths : skin.furLengths();
  const std::int32_t* tri = skin.triangles.data();
  SkinFur s;
  double lengthArea = 0.0;
  for (std::int32_t t = 0; t < skin.numTriangles(); ++t) {
    if (!triangleHasFur(skin, len, t)) continue;
    const double a = area[static_cast<std::size_t>(t)];
    const std::int32_t* v = tri + 3 * static_cast<std::int64_t>(t);
    s.area += a;
    lengthArea += a * static_cast<double>(len[v[0]] + len[v[1]] + len[v[2]]) / 3.0;
  }
  s.meanLength = s.area > 0.0 ? lengthArea / s.area : 0.0;
  return s;
}

double coatShare(const FurParams& p, int c) {
  const double share = static_cast<double>(p.undercoatShare);
  return c == kOvercoat ? 1.0 - share : share;
}

// The hair area (m^2) one hair of coat c brings on average: L_c w_c.
double hairArea(const FurParams& p, int c, const SkinFur& s) {
  const CoatParams& coat = p.coats[static_cast<std::size_t>(c)];
  const double length =
      s.meanLength * static_cast<double>(p.lengthScale) * static_cast<double>(coat.lengthFactor);
  return length * 0.5e-3 * static_cast<double>(coat.width.rootMm + coat.width.tipMm);
}

double hairsFor(const FurParams& p, const SkinFur& s, double hiddenShare) {
  double perHair = 0.0;  // sum_c share_c L_c w_c
  for (int c = 0; c < kCoatCount; ++c) perHair += coatShare(p, c) * hairArea(p, c, s);
  if (s.area <= 0.0 || perHair <= 0.0) return 0.0;
  const double tau = -std::log(1.0 - hiddenShare) / kProjectedShare;
  return std::ceil(tau * s.area / perHair);
}

}  // namespace

double hairsForCoverage(const skin::SkinMesh& skin, const FurParams& params, double hiddenShare,
                        const float* lengths) {
  return hairsFor(params, skinFur(skin, lengths), hiddenShare);
}

FurParams fitCoverageToBudget(const skin::SkinMesh& skin, FurParams params, const float* lengths) {
  if (params.coverage <= 0.0) return params;
  const double n = hairsForCoverage(skin, params, params.coverage, lengths);
  if (n <= kCoverageHairBudget) return params;
  double widen = n / kCoverageHairBudget;
  for (const CoatParams& c : params.coats)
    widen = std::min(widen, 20.0 / static_cast<double>(std::max(c.width.rootMm, c.width.tipMm)));
  for (CoatParams& c : params.coats) {
    c.width.rootMm = static_cast<float>(static_cast<double>(c.width.rootMm) * widen);
    c.width.tipMm = static_cast<float>(static_cast<double>(c.width.tipMm) * widen);
  }
  return params;
}

FurCoverage estimateCoverage(const skin::SkinMesh& skin, const FurParams& params,
                             const float* lengths) {
  const SkinFur s = skinFur(skin, lengths);
  FurCoverage f;
  f.furredAreaM2 = s.area;
  const double total =
      params.coverage > 0.0 ? hairsFor(params, s, params.coverage) : requestedHairs(params, s.area);
  for (int c = 0; c < kCoatCount; ++c) {
    const CoatParams& coat = params.coats[static_cast<std::size_t>(c)];
    CoatCoverage& k = f.coats[static_cast<std::size_t>(c)];
    k.hairs = total * coatShare(params, c);
    k.meanLengthMm = 1e3 * s.meanLength * static_cast<double>(params.lengthScale) *
                     static_cast<double>(coat.lengthFactor);
    k.meanWidthMm = 0.5 * static_cast<double>(coat.width.rootMm + coat.width.tipMm);
    if (s.area <= 0.0) continue;
    k.densityPerCm2 = k.hairs / s.area * 1e-4;
    k.opticalDepth = k.hairs / s.area * hairArea(params, c, s);
    f.opticalDepth += k.opticalDepth;
  }
  f.hiddenShare = 1.0 - std::exp(-kProjectedShare * f.opticalDepth);
  return f;
}

}  // namespace pelage::fur
