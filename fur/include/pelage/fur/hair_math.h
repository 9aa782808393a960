// The per-hair maths of Van Gelder & Wilhelms 1997, sec. 3.2 to 3.8, written once for any "lane"
// type T: float (the scalar reference, and the text the GPU shader mirrors line for line) or the
// SIMD lane types of the CPU kernel (fur/src/kernel_hwy.cpp), which supply the same helpers by ADL:
//   sqrtOf(T), floorOf(T), absOf(T), greater(T,T), lessEq(T,T), equalTo(T,T) -> mask,
//   andMask(mask,mask), pick(mask, a, b) = mask ? a : b, allOf(mask) -> bool (every lane set).
// Every function is a fixed sequence of IEEE single-precision +, -, *, /, sqrt and selects (no
// fused multiply-add, no approximations), so all lane types give bit-identical results.
#pragma once

#include <cmath>
#include <cstdint>

#include "pelage/fur/coat_shape.h"
#include "pelage/fur/hair_style.h"

namespace pelage::fur {

// ---- Scalar lane helpers (the SIMD types define the same names in their own namespaces) --------
inline float sqrtOf(float x) {
  return std::sqrt(x);
}
inline float floorOf(float x) {
  return std::floor(x);
}
inline float absOf(float x) {
  return x < 0.0f ? -x : x;
}
inline bool greater(float a, float b) {
  return a > b;
}
inline bool lessEq(float a, float b) {
  return a <= b;
}
inline bool equalTo(float a, float b) {
  return a == b;
}
inline bool andMask(bool a, bool b) {
  return a && b;
}
inline float pick(bool m, float a, float b) {
  return m ? a : b;
}
inline bool allOf(bool m) {
  return m;
}

// A 3-vector of lanes.
template <class T>
struct Vec3 {
  T x, y, z;
};

template <class T>
inline Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline Vec3<T> operator-(const Vec3<T>& a) {
  return {T(0.0f) - a.x, T(0.0f) - a.y, T(0.0f) - a.z};
}
template <class T>
inline Vec3<T> operator*(const Vec3<T>& a, const T& s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class T>
inline T dot(const Vec3<T>& a, const Vec3<T>& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
template <class T>
inline Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class M, class T>
inline Vec3<T> pick(const M& m, const Vec3<T>& a, const Vec3<T>& b) {
  return {pick(m, a.x, b.x), pick(m, a.y, b.y), pick(m, a.z, b.z)};
}
template <class T>
inline Vec3<T> splat(const float v[3]) {
  return {T(v[0]), T(v[1]), T(v[2])};
}

// v / |v|, or `fallback` where |v|^2 <= minLength2.
template <class T>
inline Vec3<T> normalizeOr(const Vec3<T>& v, const Vec3<T>& fallback, float minLength2) {
  const T len2 = dot(v, v);
  const auto ok = greater(len2, T(minLength2));
  const T inv = T(1.0f) / sqrtOf(pick(ok, len2, T(1.0f)));
  return pick(ok, v * inv, fallback);
}

// normalizeOr(v, fallback(), minLength2), with the fallback computed only when some lane needs it
// (the same bits: pick keeps v / |v| wherever |v|^2 > minLength2).
template <class T, class Fallback>
inline Vec3<T> normalizeOrElse(const Vec3<T>& v, Fallback&& fallback, float minLength2) {
  const T len2 = dot(v, v);
  const auto ok = greater(len2, T(minLength2));
  if (allOf(ok)) return v * (T(1.0f) / sqrtOf(len2));
  const T inv = T(1.0f) / sqrtOf(pick(ok, len2, T(1.0f)));
  return pick(ok, v * inv, fallback());
}

// A unit vector perpendicular to unit v: normalize(v x X), or normalize(v x Y) when |v.x| >= 0.9.
template <class T>
inline Vec3<T> perpendicularTo(const Vec3<T>& v) {
  const auto nearX = greater(absOf(v.x), T(0.9f));
  const Vec3<T> withX{T(0.0f), v.z, T(0.0f) - v.y};  // v x (1, 0, 0)
  const Vec3<T> withY{T(0.0f) - v.z, T(0.0f), v.x};  // v x (0, 1, 0)
  const Vec3<T> p = pick(nearX, withY, withX);
  return p * (T(1.0f) / sqrtOf(dot(p, p)));
}

// sin and cos of 2 pi u for u in [0, 1): quadrant reduction and Taylor polynomials of degree 9 and
// 8 on [-pi/4, pi/4] (truncation error < 3e-8). Used for the helix phase.
template <class T>
inline void sinCosTurns(const T& u, T& s, T& c) {
  const T x = u * T(4.0f);
  const T k = floorOf(x + T(0.5f));
  const T a = (x - k) * T(1.57079632679f);
  const T a2 = a * a;
  const T sa =
      a * (T(1.0f) +
           a2 * (T(-1.0f / 6.0f) +
                 a2 * (T(1.0f / 120.0f) + a2 * (T(-1.0f / 5040.0f) + a2 * T(1.0f / 362880.0f)))));
  const T ca =
      T(1.0f) +
      a2 * (T(-0.5f) + a2 * (T(1.0f / 24.0f) + a2 * (T(-1.0f / 720.0f) + a2 * T(1.0f / 40320.0f))));
  // sin(a + k pi/2), cos(a + k pi/2) for k = 0..4 (4 == 0).
  const auto q1 = equalTo(k, T(1.0f));
  const auto q2 = equalTo(k, T(2.0f));
  const auto q3 = equalTo(k, T(3.0f));
  s = pick(q1, ca, pick(q2, T(0.0f) - sa, pick(q3, T(0.0f) - ca, sa)));
  c = pick(q1, T(0.0f) - sa, pick(q2, T(0.0f) - ca, pick(q3, sa, ca)));
}

// Sec. 3.8's helix angle 2 pi turns t at curve parameter t: its sine and cosine (sinCosTurns of the
// fraction of a turn). The coat's table (makeCoatShape: curlCos, curlSin) and a hair's own turns
// (a groom's curl) take the same steps, so equal turns wind equal hairs bit for bit.
template <class T>
inline void helixTurn(const T& turns, float t, T& s, T& c) {
  const T u = turns * T(t);
  sinCosTurns(u - floorOf(u), s, c);
}

// Inputs of one hair, interpolated at its root from the triangle's vertices (sec. 3.2).
template <class T>
struct HairInput {
  Vec3<T> root;          // h = b1 v1 + b2 v2 + b3 v3 (deformed positions)
  Vec3<T> normalSum;     // b1 n1 + b2 n2 + b3 n3 (not yet normalised)
  Vec3<T> directionSum;  // b1 s1 + b2 s2 + b3 s3 (segment directions, not yet normalised)
  T length;              // b1 len1 + b2 len2 + b3 len3 (m, before scaling)
  Vec3<T> xi;            // unit-ball jitter of the weightless end (per root)
  T phase;               // helix phase in turns (per root)
  // The groom's comb (read only when CoatShape::comb): the deformed triangle's first edge
  // v2 - v1, and the root's comb in the tangent frame it spans (unpackComb).
  Vec3<T> combEdge;
  T combX, combY;
  T floppiness;     // the root's own (read only when CoatShape::perHairFloppiness)
  T segmentWeight;  // the root's own (read only when CoatShape::perHairSegmentWeight)
  T curlRadius;     // the root's own helix (read only when CoatShape::perHairCurl)
  T curlTurns;
  T widthScale;  // the root's own width scale (read only when CoatShape::perHairWidth)
};

// The polyline normal twist of one hair (sec. 3.7), per point: cos and sin of the random angle.
template <class T>
struct HairTwist {
  T cosAngle[kPolylinePoints];
  T sinAngle[kPolylinePoints];
};

// What every style needs of one hair (sec. 3.2 to 3.5): root R, skin normal n, perturbed weightless
// direction d~ (W = R + L d~), drooped direction e (E = R + L e), hair-plane normal B, length L.
template <class T>
struct HairFrame {
  Vec3<T> root;
  Vec3<T> normal;
  Vec3<T> dTilde;
  Vec3<T> e;
  Vec3<T> planeNormal;
  T length;
  T phase;
  // The helix radius (the coat's, or the hair's own with CoatShape::perHairCurl, as the GPU's
  // HairInput) and the hair's own turns (read only with perHairCurl).
  T curlRadius, curlTurns;
  // The multiple of the coat's tube radius (1, or the hair's own with CoatShape::perHairWidth).
  T widthScale;
};

// Van Gelder & Wilhelms 1997, sec. 3.2: h = b1 v1 + b2 v2 + b3 v3 (one component).
template <class T>
inline T barycentricMix(const T& b1, const T& b2, const T& b3, const T& v1, const T& v2,
                        const T& v3) {
  return (b1 * v1 + b2 * v2) + b3 * v3;
}

// Floats per packed vertex record: position xyz, fur length; normal xyz, 0; segment direction xyz,
// 0 (what the kernels and the GPU read per skin vertex).
inline constexpr int kVertexRecordFloats = 12;

// A root's comb (CoatRoots::comb): its direction times its amount a <= 1, as coordinates (x, y) in
// the root's tangent frame u = normalize(e - (e.n) n), v = n x u (e the triangle's first edge v2 -
// v1, n the interpolated skin normal), each a 16-bit signed fraction (x in the low half):
// (round(32767 x), round(32767 y)). The frame moves with the skin, so the comb does.
inline std::uint32_t packComb(float x, float y) {
  const auto q = [](float f) {
    const float c = f < -1.0f ? -1.0f : (f > 1.0f ? 1.0f : f);
    return static_cast<std::uint32_t>(static_cast<std::uint16_t>(
        static_cast<std::int16_t>(std::lround(static_cast<double>(c) * 32767.0))));
  };
  return q(x) | (q(y) << 16);
}
inline void unpackComb(std::uint32_t packed, float& x, float& y) {
  x = static_cast<float>(static_cast<std::int16_t>(packed & 0xffffu)) / 32767.0f;
  y = static_cast<float>(static_cast<std::int16_t>(packed >> 16)) / 32767.0f;
}

// Sec. 3.2: one hair's inputs at its root, interpolated from its triangle's three vertex records
// (kVertexRecordFloats each) with the barycentric entry b = (b1, b2, b3), and the root's jitter
// j = (xi x, y, z, helix phase); a length map's value at the root multiplies the interpolated
// length (1 without one: x * 1 = x exactly); `comb` is the root's packed comb (0: none);
// `floppiness`, `segmentWeight`, `curl` (radius, turns) and `widthScale` the root's own
// (CoatRoots; read only where the coat has them). The scalar form of every kernel's gather (and of
// the GPU's interpolateRoot in hair_math.glsl).
inline HairInput<float> interpolateRoot(const float* b, const float* v1, const float* v2,
                                        const float* v3, const float* j, float lengthScale = 1.0f,
                                        std::uint32_t comb = 0, float floppiness = 0.0f,
                                        float segmentWeight = 0.0f, const float* curl = nullptr,
                                        float widthScale = 1.0f) {
  const auto mix = [&](int k) { return barycentricMix(b[0], b[1], b[2], v1[k], v2[k], v3[k]); };
  HairInput<float> in{};
  in.root = {mix(0), mix(1), mix(2)};
  in.length = mix(3) * lengthScale;
  in.normalSum = {mix(4), mix(5), mix(6)};
  in.directionSum = {mix(8), mix(9), mix(10)};
  in.xi = {j[0], j[1], j[2]};
  in.phase = j[3];
  in.combEdge = {v2[0] - v1[0], v2[1] - v1[1], v2[2] - v1[2]};
  unpackComb(comb, in.combX, in.combY);
  in.floppiness = floppiness;
  in.segmentWeight = segmentWeight;
  in.curlRadius = curl ? curl[0] : 0.0f;
  in.curlTurns = curl ? curl[1] : 0.0f;
  in.widthScale = widthScale;
  return in;
}

// Sec. 3.2: the skin normal n = normalize(b1 n1 + b2 n2 + b3 n3) (U where it vanishes).
template <class T>
inline Vec3<T> skinNormal(const CoatShape& c, const HairInput<T>& in) {
  return normalizeOr(in.normalSum, splat<T>(c.up), 1e-20f);
}

// Sec. 3.2: L = (sum b_i len_i) * global scale * coat factor, times the region scale where the root
// lies in the user's 3D region (sphere: |h - c|^2 <= r^2; box: min <= h <= max).
template <class T>
inline T hairLength(const CoatShape& c, const T& interpolated, const Vec3<T>& h) {
  const T L = interpolated * T(c.lengthMul);
  if (c.regionShape == RegionShape::Sphere) {
    const Vec3<T> q = h - splat<T>(c.regionCenter);
    return L * pick(lessEq(dot(q, q), T(c.regionRadius2)), T(c.regionScale), T(1.0f));
  }
  if (c.regionShape == RegionShape::Box) {
    const auto inX = andMask(lessEq(T(c.regionMin[0]), h.x), lessEq(h.x, T(c.regionMax[0])));
    const auto inY = andMask(lessEq(T(c.regionMin[1]), h.y), lessEq(h.y, T(c.regionMax[1])));
    const auto inZ = andMask(lessEq(T(c.regionMin[2]), h.z), lessEq(h.z, T(c.regionMax[2])));
    return L * pick(andMask(andMask(inX, inY), inZ), T(c.regionScale), T(1.0f));
  }
  return L;
}

// Sec. 3.4: the weightless hair direction d = normalize((1 - w) n + w s), s = normalize(sum b_i
// s_i); d = n where the root has no segment direction (s = 0) or the blend vanishes.
template <class T>
inline Vec3<T> weightlessDirection(const Vec3<T>& n, const Vec3<T>& directionSum, const T& w) {
  const auto hasS = greater(dot(directionSum, directionSum), T(1e-12f));
  const Vec3<T> s = normalizeOr(directionSum, n, 1e-12f);
  const Vec3<T> blend = n * (T(1.0f) - w) + s * w;
  return pick(hasS, normalizeOr(blend, n, 1e-12f), n);
}

// The root's comb frame, the one frame both the rest pose (roots.cpp, packComb) and every frame
// (combedDirection) build: u = the root triangle's first edge (vertex 1 - vertex 0) projected on
// the tangent plane of the unit normal n and normalized (`fallback` where that projection
// vanishes), v = n x u.
template <class T>
struct CombFrame {
  Vec3<T> u, v;
};
template <class T>
inline CombFrame<T> combFrame(const Vec3<T>& n, const Vec3<T>& edge, const Vec3<T>& fallback) {
  const Vec3<T> u = normalizeOr(edge - n * dot(edge, n), fallback, 1e-20f);
  return {u, cross(n, u)};
}

// The groom's comb (groom.h) on the weightless direction d of sec. 3.4: the comb t = x u + y v in
// the root's tangent frame (packComb), of length a = |(x, y)| <= 1, gives d' = normalize((1 - a) d
// + t): along the comb for a = 1, d exactly for a = 0. Gravity (sec. 3.5) then bends d' as it
// would d.
template <class T>
inline Vec3<T> combedDirection(const Vec3<T>& n, const Vec3<T>& d, const HairInput<T>& in) {
  const CombFrame<T> frame = combFrame(n, in.combEdge, d);
  const Vec3<T> t = frame.u * in.combX + frame.v * in.combY;
  const T a2 = in.combX * in.combX + in.combY * in.combY;
  const Vec3<T> blend = d * (T(1.0f) - sqrtOf(a2)) + t;
  return pick(greater(a2, T(0.0f)), normalizeOr(blend, d, 1e-20f), d);
}

// Sec. 3.5 "hair end randomize": the weightless ending point W = h + L d moves to W' = W + r L xi;
// the direction used from then on is d~ = normalize(W' - h) = normalize(d + r xi) (d if r = 0).
template <class T>
inline Vec3<T> perturbedDirection(const CoatShape& c, const Vec3<T>& d, const Vec3<T>& xi) {
  if (c.endRandomize == 0.0f) return d;
  return normalizeOr(d + xi * T(c.endRandomize), d, 1e-12f);
}

// Sec. 3.5 gravity, for an up vector U (= -gravity; the paper's U = Z): cos(theta) = d~ . n,
// d' = d~ - f cos(theta) U, e = d' / |d'|, and the ending point is E = h + L e. Where |d'| ~ 0 (a
// hair straight up with f = 1) e is the coat's fixed tangent perpendicular to U. f is the coat's
// floppiness, or the hair's own (a groom's stiffness).
template <class T>
inline Vec3<T> droopDirection(const CoatShape& c, const Vec3<T>& dTilde, const Vec3<T>& n,
                              const T& f) {
  const T cosTheta = dot(dTilde, n);
  const Vec3<T> dPrime = dTilde - splat<T>(c.up) * (f * cosTheta);
  return normalizeOr(dPrime, splat<T>(c.fallbackTangent), 1e-10f);
}

// Sec. 3.7: the unit normal B of the hair plane through R, W and E (B ~ d~ x e). Degenerate planes
// (R, W, E collinear) fall back to the plane containing the skin normal (d~ x n), then to
// d~ x (an axis). B is oriented so that the in-plane normal of the chord, B x e, is on the skin
// normal's side ((B x e) . n >= 0).
template <class T>
inline Vec3<T> hairPlaneNormal(const Vec3<T>& dTilde, const Vec3<T>& e, const Vec3<T>& n) {
  const Vec3<T> b0 = cross(dTilde, e);
  const auto ok0 = greater(dot(b0, b0), T(1e-8f));
  Vec3<T> raw = b0;
  if (!allOf(ok0)) {  // the fallbacks, computed only for blocks with a degenerate plane
    const Vec3<T> b1 = cross(dTilde, n);
    const auto ok1 = greater(dot(b1, b1), T(1e-8f));
    raw = pick(ok0, b0, pick(ok1, b1, perpendicularTo(dTilde)));
  }
  const Vec3<T> b = raw * (T(1.0f) / sqrtOf(dot(raw, raw)));
  const auto flip = greater(T(0.0f), dot(cross(b, e), n));
  return pick(flip, -b, b);
}

// Sec. 3.7: polyline control point i = R + a_i (W - R) + b_i (E - R), with W - R = L d~ and
// E - R = L e passed as ld and le.
template <class T>
inline Vec3<T> polylinePoint(const CoatShape& c, int i, const Vec3<T>& root, const Vec3<T>& ld,
                             const Vec3<T>& le) {
  return (root + ld * T(c.polyA[i])) + le * T(c.polyB[i]);
}

// Sec. 3.7: the shading normal at point i, perpendicular to the segment ending there and in the
// hair plane: N_i = normalize(B x (alpha_i d~ + beta_i e)) = (alpha_i u1 + beta_i u2) / |...| with
// u1 = B x d~, u2 = B x e. As B is a unit vector perpendicular to d~ (every choice of B is) and d~,
// e are unit, |alpha u1 + beta u2|^2 = alpha^2 + beta^2 (1 - (B.e)^2) + 2 alpha beta (d~.e), passed
// as q = 1 - (B.e)^2 and cosDE = d~.e; it is never 0 because alpha_i != +-beta_i for every i.
template <class T>
inline Vec3<T> polylineNormal(const CoatShape& c, int i, const Vec3<T>& u1, const Vec3<T>& u2,
                              const T& q, const T& cosDE) {
  const T len2 = (T(c.polyAlpha2[i]) + T(c.polyBeta2[i]) * q) + T(c.polyTwoAlphaBeta[i]) * cosDE;
  const T inv = T(1.0f) / sqrtOf(len2);
  return u1 * (T(c.polyAlpha[i]) * inv) + u2 * (T(c.polyBeta[i]) * inv);
}

// Sec. 3.8: the curve's start direction n_p = the skin normal projected into the hair plane,
// normalised (d~ if n is perpendicular to the plane).
template <class T>
inline Vec3<T> curveStartDirection(const Vec3<T>& n, const Vec3<T>& b, const Vec3<T>& dTilde) {
  return normalizeOr(n - b * dot(n, b), dTilde, 1e-12f);
}

// Sec. 3.8: the cubic Bezier P0 = R, P1 = R + (L/3) n_p, P2 = R + (2/3)(E - R), P3 = E, at t_k:
// C = R + c1_k L n_p + c2_k L e (lnp = L n_p, le = L e); plus the helix ("the nurbs technique
// permits ... a helical curve"): C += curlRadius L sin(pi t) (cos(A) N1 + sin(A) B),
// A = 2 pi (turns t + phase), N1 = normalize(B x C'(t)) the in-plane normal of the curve; turns
// and radius the coat's, or the hair's own (perHairCurl: `turns`).
template <class T>
inline Vec3<T> curvePoint(const CoatShape& c, int k, const Vec3<T>& root, const Vec3<T>& lnp,
                          const Vec3<T>& le, const Vec3<T>& np, const Vec3<T>& e, const Vec3<T>& b,
                          const T& curlLength, const T& phaseSin, const T& phaseCos,
                          const T& turns) {
  const Vec3<T> base = (root + lnp * T(c.curveC1[k])) + le * T(c.curveC2[k]);
  if (!c.curl) return base;
  const Vec3<T> tangent = np * T(c.curveDc1[k]) + e * T(c.curveDc2[k]);
  const Vec3<T> n1 = normalizeOr(cross(b, tangent), np, 1e-12f);
  T turnSin = T(c.curlSin[k]), turnCos = T(c.curlCos[k]);
  if (c.perHairCurl) helixTurn(turns, c.curlT[k], turnSin, turnCos);
  const T cosA = turnCos * phaseCos - turnSin * phaseSin;
  const T sinA = turnSin * phaseCos + turnCos * phaseSin;
  const T radius = curlLength * T(c.curlEnvelope[k]);
  return base + (n1 * cosA + b * sinA) * radius;
}

// Sec. 3.8 nurbs surface: the frame of the ring around a curve point with unit tangent t:
// A = normalize(B - (B.t) t) (perpendicular to t, in the hair plane where possible), Q = t x A.
template <class T>
struct RingFrame {
  Vec3<T> a, q;
};
template <class T>
inline RingFrame<T> ringFrame(const Vec3<T>& tangentUnit, const Vec3<T>& b) {
  RingFrame<T> r;
  r.a = normalizeOrElse(
      b - tangentUnit * dot(b, tangentUnit), [&] { return perpendicularTo(tangentUnit); }, 1e-12f);
  r.q = cross(tangentUnit, r.a);
  return r;
}
// Ring direction j: cos_j Q + sin_j A (also the surface normal).
template <class T>
inline Vec3<T> tubeDirection(const CoatShape& c, int j, const RingFrame<T>& r) {
  return r.q * T(c.ringCos[j]) + r.a * T(c.ringSin[j]);
}

// Sec. 3.2 to 3.5 for one hair: interpolation, weightless direction, hair end randomize, gravity,
// hair plane (not needed by lines: B is left 0 there).
template <class T>
inline void hairFrame(const CoatShape& c, const HairInput<T>& in, HairFrame<T>& f) {
  f.root = in.root;
  f.normal = skinNormal(c, in);
  Vec3<T> d = weightlessDirection(f.normal, in.directionSum,
                                  c.perHairSegmentWeight ? in.segmentWeight : T(c.segmentWeight));
  if (c.comb) d = combedDirection(f.normal, d, in);
  f.length = hairLength(c, in.length, in.root);
  f.dTilde = perturbedDirection(c, d, in.xi);
  f.e =
      droopDirection(c, f.dTilde, f.normal, c.perHairFloppiness ? in.floppiness : T(c.floppiness));
  f.planeNormal = c.style == HairStyle::Line ? Vec3<T>{T(0.0f), T(0.0f), T(0.0f)}
                                             : hairPlaneNormal(f.dTilde, f.e, f.normal);
  f.phase = in.phase;
  f.curlRadius = c.perHairCurl ? in.curlRadius : T(c.curlRadius);
  f.curlTurns = c.perHairCurl ? in.curlTurns : T(0.0f);
  f.widthScale = c.perHairWidth ? in.widthScale : T(1.0f);
}

// Sec. 3.6: a straight line from the root to the ending point, shaded with the skin normal.
template <class T, class Sink>
inline void emitLine(const HairFrame<T>& f, Sink& sink) {
  sink(0, f.root, f.normal);
  sink(1, f.root + f.e * f.length, f.normal);
}

// Sec. 3.7: eight control points in the hair plane, a shading normal per point (twisted when the
// coat's normal randomize is on; `twist` is read only then). Point 0 is R and point 7 is E = R + L
// e exactly (a_0 = b_0 = 0, a_7 = 0, b_7 = 1).
template <class T, class Sink>
inline void emitPolyline(const CoatShape& c, const HairFrame<T>& f, const HairTwist<T>& twist,
                         Sink& sink) {
  const Vec3<T>& b = f.planeNormal;
  const Vec3<T> ld = f.dTilde * f.length;
  const Vec3<T> le = f.e * f.length;
  const Vec3<T> u1 = cross(b, f.dTilde);
  const Vec3<T> u2 = cross(b, f.e);
  const T be = dot(b, f.e);
  const T q = T(1.0f) - be * be;
  const T cosDE = dot(f.dTilde, f.e);
  // Point 0 takes the first segment's normal, which point 1 has too (the same constants).
  const Vec3<T> first = polylineNormal(c, 1, u1, u2, q, cosDE);
#pragma GCC unroll 8
  for (int i = 0; i < kPolylinePoints; ++i) {
    const Vec3<T> p =
        i == 0 ? f.root
               : (i == kPolylinePoints - 1 ? f.root + le : polylinePoint(c, i, f.root, ld, le));
    Vec3<T> nrm = i <= 1 ? first : polylineNormal(c, i, u1, u2, q, cosDE);
    if (c.twist) nrm = nrm * twist.cosAngle[i] + b * twist.sinAngle[i];
    sink(i, p, nrm);
  }
}

// The curve's shared terms (sec. 3.8).
template <class T>
struct CurveTerms {
  Vec3<T> np, lnp, le;
  T curlLength, phaseSin, phaseCos;
};
template <class T>
inline CurveTerms<T> curveTerms(const CoatShape& c, const HairFrame<T>& f) {
  CurveTerms<T> t;
  t.np = curveStartDirection(f.normal, f.planeNormal, f.dTilde);
  t.lnp = t.np * f.length;
  t.le = f.e * f.length;
  t.curlLength = f.length * f.curlRadius;
  t.phaseSin = T(0.0f);
  t.phaseCos = T(1.0f);
  if (c.curl) sinCosTurns(f.phase, t.phaseSin, t.phaseCos);
  return t;
}
template <class T>
inline Vec3<T> curvePointAt(const CoatShape& c, int k, const HairFrame<T>& f,
                            const CurveTerms<T>& t) {
  return curvePoint(c, k, f.root, t.lnp, t.le, t.np, f.e, f.planeNormal, t.curlLength, t.phaseSin,
                    t.phaseCos, f.curlTurns);
}

// Sec. 3.8 nurbs curve: K points; "Our implementation currently uses the skin normal as the shading
// normal."
template <class T, class Sink>
inline void emitCurve(const CoatShape& c, const HairFrame<T>& f, Sink& sink) {
  const CurveTerms<T> t = curveTerms(c, f);
  for (int k = 0; k < c.curvePoints; ++k) sink(k, curvePointAt(c, k, f, t), f.normal);
}

// Sec. 3.8 nurbs surface: rings of M points around the K curve points (tangents by differences of
// neighbouring points), radial normals; point k * M + j.
template <class T, class Sink>
inline void emitTube(const CoatShape& c, const HairFrame<T>& f, Sink& sink) {
  const CurveTerms<T> t = curveTerms(c, f);
  const auto hasLength = greater(f.length, T(0.0f));
  const int K = c.curvePoints, M = c.tubeSides;
  Vec3<T> prev = f.root;
  Vec3<T> cur = f.root;
  Vec3<T> next = curvePointAt(c, 1, f, t);
  for (int k = 0; k < K; ++k) {
    const Vec3<T> tangent = k == 0 ? next - cur : (k == K - 1 ? cur - prev : next - prev);
    const Vec3<T> tUnit = normalizeOr(tangent, f.dTilde, 1e-30f);
    const T coatRadius = T(c.tubeRadius[k]);
    const T radius =
        pick(hasLength, c.perHairWidth ? coatRadius * f.widthScale : coatRadius, T(0.0f));
    const RingFrame<T> ring = ringFrame(tUnit, f.planeNormal);
    for (int j = 0; j < M; ++j) {
      const Vec3<T> dir = tubeDirection(c, j, ring);
      sink(k * M + j, cur + dir * radius, dir);
    }
    if (k + 1 < K) {
      prev = cur;
      cur = next;
      if (k + 2 < K) next = curvePointAt(c, k + 2, f, t);
    }
  }
}

// Frizz (fur_params.h Frizz), beyond the paper: a 32-bit integer hash (lowbias32), the same in
// hair_math.glsl, so the CPU and the GPU draw the same random numbers.
inline std::uint32_t frizzHash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
// Lattice value `cell`, axis `axis` of hair `root` (its index in the coat): uniform in [-1, 1),
// exact in float (24 bits times 2^-23, minus 1).
inline float frizzValue(std::uint32_t seed, std::uint32_t root, std::uint32_t cell,
                        std::uint32_t axis) {
  const std::uint32_t h = frizzHash(seed + frizzHash(root + 0x9e3779b9u * (3u * cell + axis)));
  return static_cast<float>(h >> 8) * (2.0f / 16777216.0f) - 1.0f;
}
// The frizz offset of strand point k of hair `root`: frizzWeight_k (g_j + frizzBlend_k (g_{j+1} -
// g_j)), g_j the lattice vector at j = frizzCell_k.
inline void frizzOffset(const CoatShape& c, std::uint32_t root, int k, float out[3]) {
  const auto seed = static_cast<std::uint32_t>(c.frizzSeed);
  const auto cell = static_cast<std::uint32_t>(c.frizzCell[k]);
  for (std::uint32_t axis = 0; axis < 3; ++axis) {
    const float g0 = frizzValue(seed, root, cell, axis);
    const float g1 = frizzValue(seed, root, cell + 1u, axis);
    out[axis] = c.frizzWeight[k] * (g0 + c.frizzBlend[k] * (g1 - g0));
  }
}
// Adds the frizz to the points of one emitted hair (c.frizz strand points of c.frizzRing points
// each, xyz), on top of the paper's shape; strand point 0 (the root) has weight 0 and stays.
inline void addFrizz(const CoatShape& c, std::uint32_t root, float* positions) {
  for (int k = 0; k < c.frizz; ++k) {
    float o[3];
    frizzOffset(c, root, k, o);
    for (int m = 0; m < c.frizzRing; ++m) {
      float* p = positions + 3 * (k * c.frizzRing + m);
      p[0] += o[0];
      p[1] += o[1];
      p[2] += o[2];
    }
  }
}

// One hair's points from its frame, any style: calls sink(i, position, normal) for its points
// i = 0..P-1 in order.
template <class T, class Sink>
inline void emitHair(const CoatShape& c, const HairFrame<T>& f, const HairTwist<T>& twist,
                     Sink& sink) {
  switch (c.style) {
    case HairStyle::Line:
      emitLine(f, sink);
      return;
    case HairStyle::Polyline:
      emitPolyline(c, f, twist, sink);
      return;
    case HairStyle::Curve:
      emitCurve(c, f, sink);
      return;
    case HairStyle::Tube:
      emitTube(c, f, sink);
      return;
  }
}

// One hair of the coat's style from its root input: its frame (hairFrame), then its points.
template <class T, class Sink>
inline void buildHair(const CoatShape& c, const HairInput<T>& in, const HairTwist<T>& twist,
                      Sink& sink) {
  HairFrame<T> f;
  hairFrame(c, in, f);
  emitHair(c, f, twist, sink);
}

}  // namespace pelage::fur
