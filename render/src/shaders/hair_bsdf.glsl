// The hair fibre's scattering function of Chiang, Bitterli, Tappan and Burley 2016, "A practical
// and controllable hair and fur model for production path tracing" (the Principled Hair BSDF of
// Blender Cycles, which renders pelage's references): a dielectric cylinder of index eta = 1.55 and
// absorption sigma_a, its light leaving by p internal paths (p = 0: R, reflected; 1: TT,
// transmitted; 2: TRT; 3: the rest), each the product of
// - a longitudinal lobe M_p (d'Eon, Francois, Hill, Letteri and Aubry 2011, "An energy-conserving
//   hair reflectance model"): M(v, theta_i, theta_o) = exp(-sin(theta_i) sin(theta_o) / v)
//   I_0(cos(theta_i) cos(theta_o) / v) / (2 v sinh(1 / v)), I_0 the modified Bessel function,
//   v_0 = (0.726 b_m + 0.812 b_m^2 + 3.7 b_m^20)^2, v_1 = v_0 / 4, v_2 = v_3 = 4 v_0 for the
//   longitudinal roughness b_m, each lobe's theta_i tilted by the cuticle's angle alpha (2k alpha:
//   R by -2 alpha, TT by alpha, TRT by 4 alpha);
// - an attenuation A_p at the offset h across the fibre: f the Fresnel reflectance at cos(theta_o)
//   cos(gamma_o), T = exp(-2 sigma_a cos(gamma_t) / cos(theta_t)), A_0 = f, A_1 = (1 - f)^2 T,
//   A_2 = A_1 f T, A_3 = A_2 f T / (1 - f T); sin(gamma_o) = h, sin(gamma_t) = h / eta',
//   eta' = sqrt(eta^2 - sin^2(theta_o)) / cos(theta_o), sin(theta_t) = sin(theta_o) / eta;
// - an azimuthal lobe N_p: a logistic of scale s = sqrt(pi / 8) (0.265 b_n + 1.194 b_n^2 +
//   5.372 b_n^22) in phi - Phi_p, trimmed to [-pi, pi], Phi_p = 2 p gamma_t - 2 gamma_o + p pi
//   (b_n the azimuthal roughness); the rest (p = 3) spread uniformly, 1 / (2 pi);
// with sum_p M_p A_p N_p the radiance a fibre sends along w_o per unit irradiance from w_i
// (Chiang's S, as the integrator of a path tracer weighs it: pbrt's hair BSDF, Pharr 2016, "The
// implementation of a hair scattering model"). A pixel sees the fibre at every offset h, so the
// function here is its mean over h in [-1, 1] (8 midpoints). The colour c maps to sigma_a as
// Chiang's eq. 9: sigma_a = (ln c / (5.969 - 0.215 b_n + 2.532 b_n^2 - 10.73 b_n^3 + 5.574 b_n^4 +
// 0.245 b_n^5))^2 (5.888 at b_n = 0.3, Cycles' default).
const float kHairEta = 1.55;
const float kHairPi = 3.14159265;

// The fibre's absorption from its colour, Chiang's eq. 9, for the azimuthal roughness bn.
vec3 hairSigmaA(vec3 c, float bn) {
  float d = 5.969 - 0.215 * bn + 2.532 * bn * bn - 10.73 * pow(bn, 3.0) + 5.574 * pow(bn, 4.0) +
            0.245 * pow(bn, 5.0);
  vec3 l = log(clamp(c, vec3(1e-4), vec3(1.0))) / d;
  return l * l;
}

// I_0(x) by its series, sum over i < 10 of x^(2i) / (4^i (i!)^2), and log I_0 (asymptotic
// above 12).
float hairBesselI0(float x) {
  float sum = 0.0, term = 1.0, x2 = 0.25 * x * x;
  for (int i = 0; i < 10; ++i) {
    sum += term;
    term *= x2 / float((i + 1) * (i + 1));
  }
  return sum;
}
float hairLogBesselI0(float x) {
  return x > 12.0 ? x + 0.5 * (-log(2.0 * kHairPi) + log(1.0 / x) + 1.0 / (8.0 * x))
                  : log(hairBesselI0(x));
}

// d'Eon et al.'s longitudinal lobe of variance v (in log form for narrow lobes).
float hairLongitudinal(float cosI, float sinI, float cosO, float sinO, float v) {
  float a = cosI * cosO / v, b = sinI * sinO / v;
  return v <= 0.1 ? exp(hairLogBesselI0(a) - b - 1.0 / v + 0.6931 + log(1.0 / (2.0 * v)))
                  : exp(-b) * hairBesselI0(a) / (sinh(1.0 / v) * 2.0 * v);
}

// The trimmed logistic of scale s at x in [-pi, pi]; norm = 1 / (its integral over [-pi, pi]),
// hairRoughness's.
float hairAzimuthal(float x, float s, float norm) {
  float e = exp(-abs(x) / s);
  return norm * e / (s * (1.0 + e) * (1.0 + e));
}
// phi - Phi_p, wrapped to [-pi, pi].
float hairAzimuthalOffset(float phi, float p, float gammaO, float gammaT) {
  float d = phi - (2.0 * p * gammaT - 2.0 * gammaO + p * kHairPi);
  return mod(d + kHairPi, 2.0 * kHairPi) - kHairPi;
}

// The unpolarised Fresnel reflectance of a dielectric of index eta at cos(incidence) cosI.
float hairFresnel(float cosI, float eta) {
  cosI = clamp(cosI, 0.0, 1.0);
  float sinT = sqrt(max(1.0 - cosI * cosI, 0.0)) / eta;
  if (sinT >= 1.0) return 1.0;
  float cosT = sqrt(max(1.0 - sinT * sinT, 0.0));
  float rs = (eta * cosI - cosT) / (eta * cosI + cosT);
  float rp = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// One roughness of the fibre: its longitudinal variances v_0..v_3, its azimuthal scale s and the
// trimmed logistic's normalisation.
struct HairRoughness {
  vec4 v;
  float s;
  float norm;
};
HairRoughness hairRoughness(float bm, float bn) {
  float r = 0.726 * bm + 0.812 * bm * bm + 3.7 * pow(bm, 20.0);
  float v0 = r * r;
  HairRoughness h;
  h.v = vec4(v0, 0.25 * v0, 4.0 * v0, 4.0 * v0);
  h.s = 0.626657 * (0.265 * bn + 1.194 * bn * bn + 5.372 * pow(bn, 22.0));
  h.norm = 1.0 / (1.0 / (1.0 + exp(-kHairPi / h.s)) - 1.0 / (1.0 + exp(kHairPi / h.s)));
  return h;
}

// The fibre's scattering, mean over h, for a fibre of unit tangent T lit from the unit direction L
// and seen from V, absorption sigmaA and cuticle tilt alpha (radians), at two roughnesses at once
// (a and b share A_p and the geometry): fa at roughness ra, fb at rb.
void hairScattering(vec3 T, vec3 L, vec3 V, vec3 sigmaA, float alpha, HairRoughness ra,
                    HairRoughness rb, out vec3 fa, out vec3 fb) {
  float sinO = clamp(dot(T, V), -1.0, 1.0), cosO = sqrt(max(1.0 - sinO * sinO, 0.0));
  float sinI = clamp(dot(T, L), -1.0, 1.0), cosI = sqrt(max(1.0 - sinI * sinI, 0.0));
  vec3 lp = L - T * sinI, vp = V - T * sinO;
  float phi = acos(clamp(dot(lp, vp) * inversesqrt(max(dot(lp, lp) * dot(vp, vp), 1e-12)), -1.0,
                         1.0));
  // theta_i tilted by 2k alpha for each lobe (k = -1 for R, 1/2 for TT, 2 for TRT, as pbrt's
  // sin2kAlpha[1], [0] and [2]).
  float s1 = sin(alpha), c1 = cos(alpha);
  float s2 = 2.0 * c1 * s1, c2 = c1 * c1 - s1 * s1;
  float s4 = 2.0 * c2 * s2, c4 = c2 * c2 - s2 * s2;
  vec4 sinIp = vec4(sinI * c2 + cosI * s2, sinI * c1 - cosI * s1, sinI * c4 - cosI * s4, sinI);
  vec4 cosIp = abs(vec4(cosI * c2 - sinI * s2, cosI * c1 + sinI * s1, cosI * c4 + sinI * s4, cosI));
  vec4 ma, mb;
  for (int p = 0; p < 4; ++p) {
    ma[p] = hairLongitudinal(cosIp[p], sinIp[p], cosO, sinO, ra.v[p]);
    mb[p] = hairLongitudinal(cosIp[p], sinIp[p], cosO, sinO, rb.v[p]);
  }
  float sinT = sinO / kHairEta, cosT = sqrt(max(1.0 - sinT * sinT, 1e-8));
  float etap = sqrt(kHairEta * kHairEta - sinO * sinO) / max(cosO, 1e-4);
  const int n = 8;
  fa = vec3(0.0);
  fb = vec3(0.0);
  for (int k = 0; k < n; ++k) {
    float h = -1.0 + (2.0 * float(k) + 1.0) / float(n);
    float gammaO = asin(h);
    float sinGT = clamp(h / etap, -1.0, 1.0);
    float gammaT = asin(sinGT);
    vec3 t = exp(-sigmaA * (2.0 * sqrt(1.0 - sinGT * sinGT) / cosT));
    float f = hairFresnel(cosO * sqrt(max(1.0 - h * h, 0.0)), kHairEta);
    vec3 a1 = (1.0 - f) * (1.0 - f) * t, a2 = a1 * t * f, a3 = a2 * f * t / (1.0 - t * f);
    vec3 d = vec3(hairAzimuthalOffset(phi, 0.0, gammaO, gammaT),
                  hairAzimuthalOffset(phi, 1.0, gammaO, gammaT),
                  hairAzimuthalOffset(phi, 2.0, gammaO, gammaT));
    fa += f * ma[0] * hairAzimuthal(d.x, ra.s, ra.norm) +
          a1 * (ma[1] * hairAzimuthal(d.y, ra.s, ra.norm)) +
          a2 * (ma[2] * hairAzimuthal(d.z, ra.s, ra.norm)) + a3 * (ma[3] / (2.0 * kHairPi));
    fb += f * mb[0] * hairAzimuthal(d.x, rb.s, rb.norm) +
          a1 * (mb[1] * hairAzimuthal(d.y, rb.s, rb.norm)) +
          a2 * (mb[2] * hairAzimuthal(d.z, rb.s, rb.norm)) + a3 * (mb[3] / (2.0 * kHairPi));
  }
  fa /= float(n);
  fb /= float(n);
}
