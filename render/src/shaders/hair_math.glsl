// GLSL mirror of fur/include/pelage/fur/hair_math.h (lanes T = float, Vec3<T> = vec3, masks =
// bool), function for function and operation for operation, so the GPU evaluates the same formulas
// as the CPU fur model (Van Gelder & Wilhelms 1997, sec. 3.2 to 3.8). Keep the two in step: the
// parity test (tests/render/gpu_fur_test.cpp) compares every style, with random parameters, against
// the CPU.
//
// The per-coat constants (fur::CoatShape) arrive as the std430 block `cs`, whose declaration (and
// the STYLE_*, REGION_* and array-size constants) gpu_fur.cpp generates from CoatShape's member list
// and prepends to this file.

vec3 csUp() { return vec3(cs.up[0], cs.up[1], cs.up[2]); }
vec3 csFallbackTangent() { return vec3(cs.fallbackTangent[0], cs.fallbackTangent[1], cs.fallbackTangent[2]); }

// hair_math.h: dot(a, b) = (a.x * b.x + a.y * b.y) + a.z * b.z (same summation order).
float dot3(vec3 a, vec3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

// v / |v|, or `fallback` where |v|^2 <= minLength2.
vec3 normalizeOr(vec3 v, vec3 fallback, float minLength2) {
  float len2 = dot3(v, v);
  bool ok = len2 > minLength2;
  float inv = 1.0 / sqrt(ok ? len2 : 1.0);
  return ok ? v * inv : fallback;
}

// A unit vector perpendicular to unit v: normalize(v x X), or normalize(v x Y) when |v.x| >= 0.9.
vec3 perpendicularTo(vec3 v) {
  bool nearX = abs(v.x) > 0.9;
  vec3 withX = vec3(0.0, v.z, 0.0 - v.y);
  vec3 withY = vec3(0.0 - v.z, 0.0, v.x);
  vec3 p = nearX ? withY : withX;
  return p * (1.0 / sqrt(dot3(p, p)));
}

// sin and cos of 2 pi u for u in [0, 1): quadrant reduction and Taylor polynomials of degree 9 and
// 8 on [-pi/4, pi/4], the same terms as hair_math.h.
void sinCosTurns(float u, out float s, out float c) {
  float x = u * 4.0;
  float k = floor(x + 0.5);
  float a = (x - k) * 1.57079632679;
  float a2 = a * a;
  float sa = a * (1.0 + a2 * (-1.0 / 6.0 + a2 * (1.0 / 120.0 + a2 * (-1.0 / 5040.0 + a2 * (1.0 / 362880.0)))));
  float ca = 1.0 + a2 * (-0.5 + a2 * (1.0 / 24.0 + a2 * (-1.0 / 720.0 + a2 * (1.0 / 40320.0))));
  bool q1 = k == 1.0;
  bool q2 = k == 2.0;
  bool q3 = k == 3.0;
  s = q1 ? ca : (q2 ? 0.0 - sa : (q3 ? 0.0 - ca : sa));
  c = q1 ? 0.0 - sa : (q2 ? 0.0 - ca : (q3 ? sa : ca));
}

// Sec. 3.8's helix angle 2 pi turns t: its sine and cosine (hair_math.h: helixTurn).
void helixTurn(float turns, float t, out float s, out float c) {
  float u = turns * t;
  sinCosTurns(u - floor(u), s, c);
}

// Inputs of one hair, interpolated at its root (sec. 3.2).
struct HairInput {
  vec3 root;
  vec3 normalSum;
  vec3 directionSum;
  float length;
  vec3 xi;
  float phase;
  vec3 combEdge;  // the groom's comb (cs.comb): the triangle's first edge v2 - v1,
  float combX;    // and the root's comb in the tangent frame it spans
  float combY;
  float floppiness;     // the root's own (cs.perHairFloppiness: a groom's stiffness)
  float segmentWeight;  // the root's own (cs.perHairSegmentWeight: a groom's direction weight)
  float curlRadius;     // the root's own helix (cs.perHairCurl: a groom's curl)
  float curlTurns;
  float widthScale;     // the root's own (cs.perHairWidth: a groom's width scale, tubes)
  float twistCos[POLYLINE_POINTS];
  float twistSin[POLYLINE_POINTS];
};

// Sec. 3.2: h = b1 v1 + b2 v2 + b3 v3.
float barycentricMix(float b1, float b2, float b3, float v1, float v2, float v3) {
  return (b1 * v1 + b2 * v2) + b3 * v3;
}

// Sec. 3.2: one hair's inputs at its root, interpolated from its triangle's three vertices (deformed
// position p, fur length len, normal n, segment direction sd) with the barycentric entry b, the
// root's jitter j = (xi, phase), its length-map scale and its packed comb (hair_math.h:
// interpolateRoot, unpackComb: two 16-bit signed fractions, x in the low half).
HairInput interpolateRoot(vec3 b, vec3 p1, vec3 p2, vec3 p3, float len1, float len2, float len3,
                          vec3 n1, vec3 n2, vec3 n3, vec3 sd1, vec3 sd2, vec3 sd3, vec4 j,
                          float lengthScale, int comb) {
  HairInput hin;
  hin.root = vec3(barycentricMix(b.x, b.y, b.z, p1.x, p2.x, p3.x),
                  barycentricMix(b.x, b.y, b.z, p1.y, p2.y, p3.y),
                  barycentricMix(b.x, b.y, b.z, p1.z, p2.z, p3.z));
  hin.length = barycentricMix(b.x, b.y, b.z, len1, len2, len3) * lengthScale;
  hin.normalSum = vec3(barycentricMix(b.x, b.y, b.z, n1.x, n2.x, n3.x),
                       barycentricMix(b.x, b.y, b.z, n1.y, n2.y, n3.y),
                       barycentricMix(b.x, b.y, b.z, n1.z, n2.z, n3.z));
  hin.directionSum = vec3(barycentricMix(b.x, b.y, b.z, sd1.x, sd2.x, sd3.x),
                          barycentricMix(b.x, b.y, b.z, sd1.y, sd2.y, sd3.y),
                          barycentricMix(b.x, b.y, b.z, sd1.z, sd2.z, sd3.z));
  hin.xi = j.xyz;
  hin.phase = j.w;
  hin.combEdge = p2 - p1;
  hin.combX = float((comb << 16) >> 16) / 32767.0;
  hin.combY = float(comb >> 16) / 32767.0;
  hin.floppiness = cs.floppiness;
  hin.segmentWeight = cs.segmentWeight;
  hin.curlRadius = cs.curlRadius;
  hin.curlTurns = 0.0;
  hin.widthScale = 1.0;
  return hin;
}

// Sec. 3.2: the skin normal n = normalize(b1 n1 + b2 n2 + b3 n3) (U where it vanishes).
vec3 skinNormal(HairInput hin) { return normalizeOr(hin.normalSum, csUp(), 1e-20); }

// Sec. 3.2: L = (sum b_i len_i) * global scale * coat factor, times the region scale inside the
// user's 3D region.
float hairLength(float interpolated, vec3 h) {
  float L = interpolated * cs.lengthMul;
  if (cs.regionShape == REGION_SPHERE) {
    vec3 q = h - vec3(cs.regionCenter[0], cs.regionCenter[1], cs.regionCenter[2]);
    return L * (dot3(q, q) <= cs.regionRadius2 ? cs.regionScale : 1.0);
  }
  if (cs.regionShape == REGION_BOX) {
    bool inX = cs.regionMin[0] <= h.x && h.x <= cs.regionMax[0];
    bool inY = cs.regionMin[1] <= h.y && h.y <= cs.regionMax[1];
    bool inZ = cs.regionMin[2] <= h.z && h.z <= cs.regionMax[2];
    return L * ((inX && inY && inZ) ? cs.regionScale : 1.0);
  }
  return L;
}

// Sec. 3.4: d = normalize((1 - w) n + w s), s = normalize(sum b_i s_i); d = n without s.
vec3 weightlessDirection(vec3 n, vec3 directionSum, float w) {
  bool hasS = dot3(directionSum, directionSum) > 1e-12;
  vec3 s = normalizeOr(directionSum, n, 1e-12);
  vec3 blend = n * (1.0 - w) + s * w;
  return hasS ? normalizeOr(blend, n, 1e-12) : n;
}

// The groom's comb on d (hair_math.h: combedDirection): d' = normalize((1 - a) d + t), t = x u + y v
// in the root's tangent frame, a = |(x, y)|; d where a = 0.
vec3 combedDirection(vec3 n, vec3 d, HairInput hin) {
  vec3 u = normalizeOr(hin.combEdge - n * dot3(hin.combEdge, n), d, 1e-20);
  vec3 t = u * hin.combX + cross(n, u) * hin.combY;
  float a2 = hin.combX * hin.combX + hin.combY * hin.combY;
  vec3 blend = d * (1.0 - sqrt(a2)) + t;
  return a2 > 0.0 ? normalizeOr(blend, d, 1e-20) : d;
}

// Frizz (hair_math.h: frizzHash, frizzValue, frizzOffset): the same integer hash, so the same
// lattice values bit for bit.
uint frizzHash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
float frizzValue(uint seed, uint root, uint cell, uint axis) {
  uint h = frizzHash(seed + frizzHash(root + 0x9e3779b9u * (3u * cell + axis)));
  return float(h >> 8) * (2.0 / 16777216.0) - 1.0;
}
vec3 frizzOffset(uint root, int k) {
  uint seed = uint(cs.frizzSeed);
  uint cell = uint(cs.frizzCell[k]);
  vec3 o;
  for (uint axis = 0u; axis < 3u; ++axis) {
    float g0 = frizzValue(seed, root, cell, axis);
    float g1 = frizzValue(seed, root, cell + 1u, axis);
    o[axis] = cs.frizzWeight[k] * (g0 + cs.frizzBlend[k] * (g1 - g0));
  }
  return o;
}

// Sec. 3.5 hair end randomize: d~ = normalize(d + r xi).
vec3 perturbedDirection(vec3 d, vec3 xi) {
  if (cs.endRandomize == 0.0) return d;
  return normalizeOr(d + xi * cs.endRandomize, d, 1e-12);
}

// Sec. 3.5 gravity: cos(theta) = d~ . n, d' = d~ - f cos(theta) U, e = d' / |d'| (f the coat's
// floppiness or the hair's own).
vec3 droopDirection(vec3 dTilde, vec3 n, float f) {
  float cosTheta = dot3(dTilde, n);
  vec3 dPrime = dTilde - csUp() * (f * cosTheta);
  return normalizeOr(dPrime, csFallbackTangent(), 1e-10);
}

// Sec. 3.7: the unit normal B of the hair plane through R, W and E, oriented so that B x e lies on
// the skin normal's side.
vec3 hairPlaneNormal(vec3 dTilde, vec3 e, vec3 n) {
  vec3 b0 = cross(dTilde, e);
  vec3 b1 = cross(dTilde, n);
  bool ok0 = dot3(b0, b0) > 1e-8;
  bool ok1 = dot3(b1, b1) > 1e-8;
  vec3 raw = ok0 ? b0 : (ok1 ? b1 : perpendicularTo(dTilde));
  vec3 b = raw * (1.0 / sqrt(dot3(raw, raw)));
  bool flip = 0.0 > dot3(cross(b, e), n);
  return flip ? -b : b;
}

// Sec. 3.7: polyline control point i = R + a_i (W - R) + b_i (E - R).
vec3 polylinePoint(int i, vec3 root, vec3 ld, vec3 le) { return (root + ld * cs.polyA[i]) + le * cs.polyB[i]; }

// Sec. 3.7: the shading normal at point i, perpendicular to the segment ending there and in the
// hair plane: N_i = (alpha_i u1 + beta_i u2) / |...|, with |alpha u1 + beta u2|^2 = alpha^2 +
// beta^2 q + 2 alpha beta cosDE, q = 1 - (B.e)^2, cosDE = d~.e (hair_math.h: polylineNormal).
vec3 polylineNormal(int i, vec3 u1, vec3 u2, float q, float cosDE) {
  float len2 = (cs.polyAlpha2[i] + cs.polyBeta2[i] * q) + cs.polyTwoAlphaBeta[i] * cosDE;
  float inv = 1.0 / sqrt(len2);
  return u1 * (cs.polyAlpha[i] * inv) + u2 * (cs.polyBeta[i] * inv);
}

// Sec. 3.8: n_p = the skin normal projected into the hair plane, normalised.
vec3 curveStartDirection(vec3 n, vec3 b, vec3 dTilde) { return normalizeOr(n - b * dot3(n, b), dTilde, 1e-12); }

// Sec. 3.8: the cubic Bezier (R, R + L/3 n_p, R + 2/3 (E - R), E) at t_k, plus the helix (the
// coat's turns, or the hair's own `turns` with cs.perHairCurl).
vec3 curvePoint(int k, vec3 root, vec3 lnp, vec3 le, vec3 np, vec3 e, vec3 b, float curlLength,
                float phaseSin, float phaseCos, float turns) {
  vec3 base = (root + lnp * cs.curveC1[k]) + le * cs.curveC2[k];
  if (cs.curl == 0) return base;
  vec3 tangent = np * cs.curveDc1[k] + e * cs.curveDc2[k];
  vec3 n1 = normalizeOr(cross(b, tangent), np, 1e-12);
  float turnSin = cs.curlSin[k], turnCos = cs.curlCos[k];
  if (cs.perHairCurl != 0) helixTurn(turns, cs.curlT[k], turnSin, turnCos);
  float cosA = turnCos * phaseCos - turnSin * phaseSin;
  float sinA = turnSin * phaseCos + turnCos * phaseSin;
  float radius = curlLength * cs.curlEnvelope[k];
  return base + (n1 * cosA + b * sinA) * radius;
}

// Sec. 3.8 nurbs surface: ring direction j around a curve point with unit tangent t.
vec3 tubeDirection(int j, vec3 tangentUnit, vec3 b) {
  vec3 a = normalizeOr(b - tangentUnit * dot3(b, tangentUnit), perpendicularTo(tangentUnit), 1e-12);
  vec3 q = cross(tangentUnit, a);
  return q * cs.ringCos[j] + a * cs.ringSin[j];
}

// The sink: the including shader defines void emitPoint(int i, vec3 position, vec3 normal).
void emitPoint(int i, vec3 p, vec3 n);

// One hair, any style: emitPoint(i, position, normal) for i = 0..P-1 in order (buildHair).
void buildHair(HairInput hin) {
  vec3 root = hin.root;
  vec3 n = skinNormal(hin);
  vec3 d = weightlessDirection(n, hin.directionSum, hin.segmentWeight);
  if (cs.comb != 0) d = combedDirection(n, d, hin);
  float L = hairLength(hin.length, root);
  vec3 dTilde = perturbedDirection(d, hin.xi);
  vec3 e = droopDirection(dTilde, n, hin.floppiness);
  vec3 le = e * L;
  if (cs.style == STYLE_LINE) {
    // Sec. 3.6: a straight line from the root to the ending point, shaded with the skin normal.
    emitPoint(0, root, n);
    emitPoint(1, root + le, n);
    return;
  }
  vec3 b = hairPlaneNormal(dTilde, e, n);
  if (cs.style == STYLE_POLYLINE) {
    // Sec. 3.7 (hair_math.h: emitPolyline): point 0 is R and point 7 is E = R + L e exactly; point
    // 0 takes the first segment's normal.
    vec3 ld = dTilde * L;
    vec3 u1 = cross(b, dTilde);
    vec3 u2 = cross(b, e);
    float be = dot3(b, e);
    float q = 1.0 - be * be;
    float cosDE = dot3(dTilde, e);
    vec3 first = polylineNormal(1, u1, u2, q, cosDE);
    for (int i = 0; i < POLYLINE_POINTS; ++i) {
      vec3 p = i == 0 ? root
                      : (i == POLYLINE_POINTS - 1 ? root + le : polylinePoint(i, root, ld, le));
      vec3 nrm = i <= 1 ? first : polylineNormal(i, u1, u2, q, cosDE);
      if (cs.twist != 0) nrm = nrm * hin.twistCos[i] + b * hin.twistSin[i];
      emitPoint(i, p, nrm);
    }
    return;
  }
  vec3 np = curveStartDirection(n, b, dTilde);
  vec3 lnp = np * L;
  float phaseSin = 0.0, phaseCos = 1.0;
  if (cs.curl != 0) sinCosTurns(hin.phase, phaseSin, phaseCos);
  float curlLength = L * hin.curlRadius;
  int K = cs.curvePoints;
  if (cs.style == STYLE_CURVE) {
    // Sec. 3.8: "Our implementation currently uses the skin normal as the shading normal."
    for (int k = 0; k < K; ++k) emitPoint(k, curvePoint(k, root, lnp, le, np, e, b, curlLength, phaseSin, phaseCos, hin.curlTurns), n);
    return;
  }
  // Tube: rings around the tessellated curve; tangents by differences of neighbouring points.
  bool hasLength = L > 0.0;
  int M = cs.tubeSides;
  vec3 prev = root;
  vec3 cur = root;
  vec3 next = curvePoint(1, root, lnp, le, np, e, b, curlLength, phaseSin, phaseCos, hin.curlTurns);
  for (int k = 0; k < K; ++k) {
    vec3 tangent = k == 0 ? next - cur : (k == K - 1 ? cur - prev : next - prev);
    vec3 tUnit = normalizeOr(tangent, dTilde, 1e-30);
    float coatRadius = cs.tubeRadius[k];
    float radius = hasLength ? (cs.perHairWidth != 0 ? coatRadius * hin.widthScale : coatRadius) : 0.0;
    for (int j = 0; j < M; ++j) {
      vec3 dir = tubeDirection(j, tUnit, b);
      emitPoint(k * M + j, cur + dir * radius, dir);
    }
    if (k + 1 < K) {
      prev = cur;
      cur = next;
      if (k + 2 < K) next = curvePoint(k + 2, root, lnp, le, np, e, b, curlLength, phaseSin, phaseCos, hin.curlTurns);
    }
  }
}
