#include "pelage/fur/coverage.h"

#include <algorithm>
#include <cmath>

#include "pelage/fur/roots.h"

namespace pelage::fur {
namespace {

// The furred area (m^2) and the area-weighted mean of the vertex fur length over it (m): a
// triangle's mean of the linear interpolation of its vertex lengths is the mean of the three.
// With a groom, also the means over each coat's hairs (the triangles weighted by area times their
// vertices' mean density, as growRoots shares the hairs out) of the length, the width scale and
// their product (neutral without the groom's arrays: the area-weighted length, 1, the length).
struct SkinFur {
  double area = 0.0, meanLength = 0.0;
  std::array<double, kCoatCount> hairLength{}, hairScale{}, hairLengthScale{};
};

// The mean over a triangle of the product of two linear interpolants of vertex values f and g:
// (sum_i f_i g_i + (sum_i f_i)(sum_i g_i)) / 12.
double productMean(const std::array<double, 3>& f, const std::array<double, 3>& g) {
  return (f[0] * g[0] + f[1] * g[1] + f[2] * g[2] + (f[0] + f[1] + f[2]) * (g[0] + g[1] + g[2])) /
         12.0;
}

SkinFur skinFur(const skin::SkinMesh& skin, const float* lengths,
                const VertexGroom* groom = nullptr) {
  const std::vector<double> area = triangleAreas(skin);
  const float* len = lengths ? lengths : skin.furLengths();
  const std::size_t nV = static_cast<std::size_t>(skin.numVertices());
  const bool density = groom && groom->density.size() == nV;
  const bool scaled = groom && groom->widthScale.size() == nV;
  const std::int32_t* tri = skin.triangles.data();
  SkinFur s;
  double lengthArea = 0.0, weighted = 0.0;
  std::array<double, kCoatCount> length{}, scale{}, lengthScale{};
  for (std::int32_t t = 0; t < skin.numTriangles(); ++t) {
    if (!triangleHasFur(skin, len, t)) continue;
    const double a = area[static_cast<std::size_t>(t)];
    const std::int32_t* v = tri + 3 * static_cast<std::int64_t>(t);
    const std::array<double, 3> l{len[v[0]], len[v[1]], len[v[2]]};
    const double meanL = (l[0] + l[1] + l[2]) / 3.0;
    s.area += a;
    // (Summed in float as before: the area-weighted mean, and so a coverage's hair count,
    // stays bit for bit what it was.)
    lengthArea += a * static_cast<double>(len[v[0]] + len[v[1]] + len[v[2]]) / 3.0;
    const double w = density ? a * static_cast<double>(triangleDensity(groom->density, v)) : a;
    weighted += w;
    for (int c = 0; c < kCoatCount; ++c) {
      std::array<double, 3> k{1.0, 1.0, 1.0};
      if (scaled)
        for (int i = 0; i < 3; ++i)
          k[static_cast<std::size_t>(i)] =
              static_cast<double>(groom->widthScale[static_cast<std::size_t>(v[i])][c]);
      const std::size_t cs = static_cast<std::size_t>(c);
      length[cs] += w * meanL;
      scale[cs] += w * (k[0] + k[1] + k[2]) / 3.0;
      lengthScale[cs] += w * (scaled ? productMean(l, k) : meanL);
    }
  }
  s.meanLength = s.area > 0.0 ? lengthArea / s.area : 0.0;
  for (std::size_t c = 0; c < kCoatCount; ++c) {
    s.hairLength[c] = weighted > 0.0 ? length[c] / weighted : 0.0;
    s.hairScale[c] = weighted > 0.0 ? scale[c] / weighted : 1.0;
    s.hairLengthScale[c] = weighted > 0.0 ? lengthScale[c] / weighted : 0.0;
  }
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
                             const float* lengths, const VertexGroom* groom) {
  const SkinFur s = skinFur(skin, lengths, groom);
  FurCoverage f;
  f.furredAreaM2 = s.area;
  const double total =
      params.coverage > 0.0 ? hairsFor(params, s, params.coverage) : requestedHairs(params, s.area);
  for (int c = 0; c < kCoatCount; ++c) {
    const std::size_t cs = static_cast<std::size_t>(c);
    const CoatParams& coat = params.coats[cs];
    CoatCoverage& k = f.coats[cs];
    const double lengthFactor =
        static_cast<double>(params.lengthScale) * static_cast<double>(coat.lengthFactor);
    const double width = 0.5e-3 * static_cast<double>(coat.width.rootMm + coat.width.tipMm);
    k.hairs = total * coatShare(params, c);
    k.meanLengthMm = 1e3 * s.hairLength[cs] * lengthFactor;
    k.meanWidthMm = 1e3 * width * s.hairScale[cs];
    if (s.area <= 0.0) continue;
    k.densityPerCm2 = k.hairs / s.area * 1e-4;
    k.opticalDepth = k.hairs / s.area * s.hairLengthScale[cs] * lengthFactor * width;
    f.opticalDepth += k.opticalDepth;
  }
  f.hiddenShare = 1.0 - std::exp(-kProjectedShare * f.opticalDepth);
  return f;
}

}  // namespace pelage::fur
