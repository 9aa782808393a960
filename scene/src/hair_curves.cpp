#include "hair_curves.h"

#include <algorithm>

#include "pelage/util/error.h"

namespace pelage::scene::detail {

void hairCenterLine(const fur::HairBuffers& b, std::int64_t h, float* out) {
  const int K = b.layout.strandPoints, M = b.layout.ringSides;
  const float* p = b.positions.data() + h * b.layout.pointsPerHair() * 3;
  if (M == 1) {
    std::copy(p, p + K * 3, out);
    return;
  }
  const float inv = 1.0f / static_cast<float>(M);
  for (int k = 0; k < K; ++k) {
    float s[3] = {0.0f, 0.0f, 0.0f};
    for (int j = 0; j < M; ++j)
      for (int a = 0; a < 3; ++a) s[a] += p[(k * M + j) * 3 + a];
    for (int a = 0; a < 3; ++a) out[k * 3 + a] = s[a] * inv;
  }
}

void bezierFromTessellation(const fur::CoatShape& shape, const float* points, float* control) {
  const int K = shape.curvePoints;
  const float* R = points;
  const float* E = points + (K - 1) * 3;
  auto d = [](float v) { return static_cast<double>(v); };
  double num[3] = {0.0, 0.0, 0.0}, den = 0.0;
  for (int k = 1; k < K - 1; ++k) {
    const double c1 = d(shape.curveC1[k]), c2 = d(shape.curveC2[k]);
    for (int a = 0; a < 3; ++a)
      num[a] += c1 * (d(points[k * 3 + a]) - d(R[a]) - c2 * (d(E[a]) - d(R[a])));
    den += c1 * c1;
  }
  for (int a = 0; a < 3; ++a) {
    const double lnp = den > 0.0 ? num[a] / den : 0.0;  // L n_p
    const double e = d(E[a]) - d(R[a]);                 // E - R
    control[0 + a] = R[a];
    control[3 + a] = static_cast<float>(d(R[a]) + lnp / 3.0);
    control[6 + a] = static_cast<float>(d(R[a]) + 2.0 * e / 3.0);
    control[9 + a] = E[a];
  }
}

void bezierThroughPoints(const float* points, int K, float* control) {
  PELAGE_CHECK(K >= 2);
  for (int a = 0; a < 3; ++a) control[a] = points[a];
  for (int k = 0; k + 1 < K; ++k) {
    const int prev = std::max(k - 1, 0), next2 = std::min(k + 2, K - 1);
    // Catmull-Rom tangents m_k = (p_{k+1} - p_{k-1}) / 2 (one-sided at the ends: (p_1 - p_0)), and
    // the Bezier handles p_k + m_k / 3, p_{k+1} - m_{k+1} / 3.
    const float s0 = k == 0 ? 1.0f : 0.5f;
    const float s1 = k + 2 > K - 1 ? 1.0f : 0.5f;
    for (int a = 0; a < 3; ++a) {
      const float m0 = (points[(k + 1) * 3 + a] - points[prev * 3 + a]) * s0;
      const float m1 = (points[next2 * 3 + a] - points[k * 3 + a]) * s1;
      control[(3 * k + 1) * 3 + a] = points[k * 3 + a] + m0 / 3.0f;
      control[(3 * k + 2) * 3 + a] = points[(k + 1) * 3 + a] - m1 / 3.0f;
      control[(3 * k + 3) * 3 + a] = points[(k + 1) * 3 + a];
    }
  }
}

void hairCurve(const fur::HairBuffers& b, const fur::CoatShape& shape, std::int64_t h,
               std::vector<float>& centerScratch, float* out) {
  const fur::HairLayout& layout = b.layout;
  switch (layout.basis) {
    case fur::CurveBasis::Linear:
      hairCenterLine(b, h, out);
      return;
    case fur::CurveBasis::Bezier:
      centerScratch.resize(static_cast<std::size_t>(layout.strandPoints) * 3);
      hairCenterLine(b, h, centerScratch.data());
      if (layout.curl)
        bezierThroughPoints(centerScratch.data(), layout.strandPoints, out);
      else
        bezierFromTessellation(shape, centerScratch.data(), out);
      return;
  }
}

}  // namespace pelage::scene::detail
