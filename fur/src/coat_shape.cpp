// The coat shape (coat_shape.h): a preset's coat as the per-hair maths' constants.
#include "pelage/fur/coat_shape.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "pelage/fur/fur_params.h"
#include "pelage/fur/hair_layout.h"
#include "pelage/fur/hair_math.h"
#include "pelage/fur/roots.h"

namespace pelage::fur {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

HairLayout coatLayout(const FurParams& params, const FurRoots& roots, int coat) {
  const auto ci = static_cast<std::size_t>(coat);
  HairLayout l = hairLayout(params.coats[ci]);
  if (!roots.coats[ci].curlRadius.empty() && usesCurveParams(l.style)) l.curl = true;
  return l;
}

CoatShape makeCoatShape(const FurParams& params, int coat) {
  const CoatParams& cp = params.coats[static_cast<std::size_t>(coat)];
  CoatShape c;
  c.style = cp.style;
  c.points = hairLayout(cp).pointsPerHair();
  c.lengthMul = params.lengthScale * cp.lengthFactor;
  c.segmentWeight = cp.segmentDirectionWeight;
  c.endRandomize = cp.hairEndRandomize;
  c.floppiness = floppiness(cp.stiffness);
  const Eigen::Vector3f up = params.up.normalized();
  // A fixed tangent perpendicular to U for hairs that gravity leaves with no direction.
  const Eigen::Vector3f axis =
      std::abs(up.x()) > 0.9f ? Eigen::Vector3f::UnitY() : Eigen::Vector3f::UnitX();
  const Eigen::Vector3f tangent = up.cross(axis).normalized();
  for (int k = 0; k < 3; ++k) {
    c.up[k] = up[k];
    c.fallbackTangent[k] = tangent[k];
  }
  c.twist = cp.style == HairStyle::Polyline && cp.normalRandomize > 0.0f;
  const LengthRegion& reg = params.lengthRegion;
  c.regionShape = reg.shape;
  c.regionScale = reg.scale;
  c.regionRadius2 = reg.radius * reg.radius;
  for (int k = 0; k < 3; ++k) {
    c.regionCenter[k] = reg.center[k];
    c.regionMin[k] = reg.boxMin[k];
    c.regionMax[k] = reg.boxMax[k];
  }
  // Van Gelder & Wilhelms 1997, sec. 3.7 (Figure 3): template a(t) = 2 lambda t (1 - t),
  // b(t) = t^2, lambda = 0.5, t_i = i / 7.
  constexpr double lambda = 0.5;
  double a[kPolylinePoints], b[kPolylinePoints];
  for (int i = 0; i < kPolylinePoints; ++i) {
    const double t = i / double(kPolylinePoints - 1);
    a[i] = 2.0 * lambda * t * (1.0 - t);
    b[i] = t * t;
    c.polyA[i] = static_cast<float>(a[i]);
    c.polyB[i] = static_cast<float>(b[i]);
  }
  for (int i = 0; i < kPolylinePoints; ++i) {
    const int s = i == 0 ? 1 : i;  // point 0 uses the first segment
    const double alpha = a[s] - a[s - 1], beta = b[s] - b[s - 1];
    c.polyAlpha[i] = static_cast<float>(alpha);
    c.polyBeta[i] = static_cast<float>(beta);
    c.polyAlpha2[i] = static_cast<float>(alpha * alpha);
    c.polyBeta2[i] = static_cast<float>(beta * beta);
    c.polyTwoAlphaBeta[i] = static_cast<float>(2.0 * alpha * beta);
  }
  // Sec. 3.8: Bezier weights of R + c1 L n_p + c2 L e at t_k = k / (K - 1).
  const int K = std::clamp(cp.curvePoints, 2, kMaxCurvePoints);
  c.curvePoints = K;
  c.curl = cp.curlRadius > 0.0f && usesCurveParams(cp.style);
  c.curlRadius = c.curl ? cp.curlRadius : 0.0f;
  for (int k = 0; k < K; ++k) {
    const double t = k / double(K - 1);
    c.curveC1[k] = static_cast<float>((1 - t) * (1 - t) * t);
    c.curveC2[k] = static_cast<float>(2 * (1 - t) * t * t + t * t * t);
    c.curveDc1[k] = static_cast<float>((1 - t) * (1 - 3 * t));
    c.curveDc2[k] = static_cast<float>(4 * t - 3 * t * t);
    const bool end = k == 0 || k == K - 1;
    c.curlEnvelope[k] = end ? 0.0f : static_cast<float>(std::sin(kPi * t));
    c.curlT[k] = static_cast<float>(t);
    helixTurn(cp.curlTurns, c.curlT[k], c.curlSin[k], c.curlCos[k]);
    // The tube's radius: half the coat's width (the one taper, StrandWidth::metersAt).
    c.tubeRadius[k] = 0.5f * cp.width.metersAt(static_cast<float>(t));
  }
  c.curveC1[K - 1] = 0.0f;  // the curve ends exactly at E
  c.curveC2[K - 1] = 1.0f;
  const int M = std::clamp(cp.tubeSides, 3, kMaxTubeSides);
  c.tubeSides = M;
  // Frizz (fur_params.h): per strand point, the weight amplitude t^tipWeight, the lattice cell and
  // the smoothstep blend of t * frequency.
  if (cp.frizz.amplitudeMm > 0.0f) {
    const HairLayout layout = hairLayout(cp);
    c.frizzRing = layout.ringSides;
    c.frizz = layout.strandPoints;
    for (int k = 0; k < c.frizz; ++k) {
      const double t = k / double(c.frizz - 1);
      const double x = t * static_cast<double>(cp.frizz.frequency);
      const double cell = std::floor(x), f = x - cell;
      c.frizzWeight[k] = static_cast<float>(1e-3 * static_cast<double>(cp.frizz.amplitudeMm) *
                                            std::pow(t, static_cast<double>(cp.frizz.tipWeight)));
      c.frizzCell[k] = static_cast<float>(cell);
      c.frizzBlend[k] = static_cast<float>(f * f * (3.0 - 2.0 * f));
    }
  }
  for (int j = 0; j < M; ++j) {
    c.ringCos[j] = static_cast<float>(std::cos(2 * kPi * j / M));
    c.ringSin[j] = static_cast<float>(std::sin(2 * kPi * j / M));
  }
  return c;
}

CoatShape makeCoatShape(const FurParams& params, const FurRoots& roots, int coat) {
  CoatShape c = makeCoatShape(params, coat);
  const CoatRoots& cr = roots.coats[static_cast<std::size_t>(coat)];
  c.comb = cr.comb.empty() ? 0 : 1;
  c.perHairFloppiness = cr.floppiness.empty() ? 0 : 1;
  c.perHairSegmentWeight = cr.segmentWeight.empty() ? 0 : 1;
  // A groom's curl winds each hair by its own helix (curve and tube styles, as the coat's).
  c.perHairCurl =
      !cr.curlRadius.empty() && usesCurveParams(params.coats[static_cast<std::size_t>(coat)].style);
  if (c.perHairCurl) c.curl = 1;
  // A groom's width scale thickens each tube by its own; strands are widened where drawn.
  c.perHairWidth = !cr.widthScale.empty() &&
                   params.coats[static_cast<std::size_t>(coat)].style == HairStyle::Tube;
  const std::uint64_t seed = coatSeed(roots.seed, coat);
  c.frizzSeed = std::bit_cast<std::int32_t>(static_cast<std::uint32_t>(seed ^ (seed >> 32)));
  return c;
}

}  // namespace pelage::fur
