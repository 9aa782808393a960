// Lighting shared by the skin and hair fragment shaders: one directional key light plus ambient,
// an optional shadow map, the paper's Phong model, the Kajiya-Kay and Marschner hair models.
uniform vec3 uLightDir;      // world, unit, towards the light
uniform vec3 uLightColor;
uniform vec3 uAmbientLight;
uniform vec3 uEye;           // world camera position
uniform float uAlongFibreDarkening;  // k_v below (Light::alongFibreDarkening)
uniform float uAlongFibreSaturation;  // k_c below (Light::alongFibreSaturation)
uniform float uLightAlongFibreDarkening;  // k_l below (Light::lightAlongFibreDarkening)
uniform float uCoatBacklitDarkening;  // k_b below (Light::coatBacklitDarkening)
// Which of the frame's light it shows (scene::LightPass): 0 all, 1 the hairs', 2 the physical
// model's fibre part, 3 its coat part, 4 the skin's. Every pass keeps the coverage.
uniform int uLightPass;
const int kPassAll = 0;
const int kPassHair = 1;
const int kPassFibre = 2;
const int kPassCoat = 3;
const int kPassSkin = 4;
// Whether the pass shows the skin's light, the coat's (the physical model's coat part; under the
// other shadings, the hair's whole light; scene::showsCoatLight) and the physical model's fibre
// part.
bool skinShown() { return uLightPass == kPassAll || uLightPass == kPassSkin; }
bool coatShown() { return uLightPass <= kPassHair || uLightPass == kPassCoat; }
bool fibreShown() { return uLightPass <= kPassHair || uLightPass == kPassFibre; }
// The skin's light c as the pass shows it.
vec3 skinPassed(vec3 c) { return skinShown() ? c : vec3(0.0); }
// A hair's light c under a shading without the physical model's parts as the pass shows it.
vec3 hairPassed(vec3 c) { return coatShown() ? c : vec3(0.0); }
uniform bool uShadows;
uniform mat4 uLightViewProj;
layout(binding = 0) uniform sampler2DShadow uShadowMap;

// The fur's own shadow (deep opacity maps, deep_opacity.frag): the fraction of the key light that
// passes the hairs between the light and worldPos. The opacity in front of the point is read from
// the layers, linear between their ends (0 at z0, the nearest hair), and light passes it as
// through independent hairs of coverage a_i: prod (1 - a_i) ~ exp(-sum a_i).
uniform bool uSelfShadow;
uniform vec4 uOpacityLayerEnds;  // as deep_opacity.frag's uLayers
uniform float uOpacityDepthScale;
layout(binding = 5) uniform sampler2D uOpacityDepth;  // z0, low-passed (opacity_blur.frag)
layout(binding = 6) uniform sampler2D uOpacityMap;    // the four layers' opacity, low-passed
float furTransmittance(vec3 q) {
  if (!uSelfShadow) return 1.0;
  float z0 = textureLod(uOpacityDepth, q.xy, 0.0).r;
  float dz = (q.z - z0) * uOpacityDepthScale;
  if (dz <= 0.0) return 1.0;
  vec4 o = textureLod(uOpacityMap, q.xy, 0.0);  // low-passed (opacity_blur.frag)
  vec4 d = uOpacityLayerEnds;
  float opacity = dz < d.x   ? o.x * dz / d.x
                  : dz < d.y ? mix(o.x, o.y, (dz - d.x) / (d.y - d.x))
                  : dz < d.z ? mix(o.y, o.z, (dz - d.y) / (d.z - d.y))
                  : dz < d.w ? mix(o.z, o.w, (dz - d.z) / (d.w - d.z))
                             : o.w;
  return exp(-opacity);
}

// The key light reaching worldPos, in two factors: the body's (3x3 percentage-closer filtering of
// the shadow map: the skin's shadow, and the hairs' without self-shadowing) in x, the fur's
// transmittance in y.
vec2 shadowFactors(vec3 worldPos, float bias) {
  if (!uShadows && !uSelfShadow) return vec2(1.0);
  vec4 p = uLightViewProj * vec4(worldPos, 1.0);
  vec3 q = p.xyz / p.w * 0.5 + 0.5;
  if (any(lessThan(q, vec3(0.0))) || any(greaterThan(q, vec3(1.0)))) return vec2(1.0);
  float fur = furTransmittance(q);
  if (!uShadows) return vec2(1.0, fur);
  vec2 texel = 1.0 / vec2(textureSize(uShadowMap, 0));
  float s = 0.0;
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x) s += texture(uShadowMap, vec3(q.xy + vec2(x, y) * texel, q.z - bias));
  return vec2(s / 9.0, fur);
}
// Fraction of the key light reaching worldPos: the two factors' product.
float shadowFactor(vec3 worldPos, float bias) {
  vec2 f = shadowFactors(worldPos, bias);
  return f.x * f.y;
}

// The paper's lighting (sec. 3.2: "Hair is given a user-defined material type consisting of
// ambient, diffuse, and specular reflectivity", lit by the GL light model):
//   c = Ka La + s (Kd Ld max(N.L, 0) + Ks Ld max(N.H, 0)^shininess),  H = normalize(L + V),
// s the shadow factor. N is the shading normal each hair style defines (secs. 3.6 to 3.8).
vec3 phong(vec3 N, vec3 P, vec3 Ka, vec3 Kd, vec3 Ks, float shininess, float s) {
  vec3 V = normalize(uEye - P);
  vec3 H = normalize(uLightDir + V);
  float nl = max(dot(N, uLightDir), 0.0);
  float nh = nl > 0.0 ? max(dot(N, H), 0.0) : 0.0;
  // (GLSL leaves pow(0, y) undefined for y <= 0: no highlight without light.)
  float spec = nh > 0.0 ? pow(nh, shininess) : 0.0;
  return Ka * uAmbientLight + s * uLightColor * (Kd * nl + Ks * spec);
}

// Kajiya & Kay 1989, "Rendering fur with three dimensional textures" (the paper's ref. [5]): a hair
// is a thin cylinder with unit tangent T;
//   diffuse  = Kd sin(T, L),
//   specular = Ks max(sin(T, L) sin(T, V) - (T.L)(T.V), 0)^shininess
// (brightest where V lies on the cone of mirror directions of L around T).
vec3 kajiyaKay(vec3 T, vec3 P, vec3 Ka, vec3 Kd, vec3 Ks, float shininess, float s) {
  vec3 V = normalize(uEye - P);
  float tl = dot(T, uLightDir);
  float tv = dot(T, V);
  float sinTL = sqrt(max(1.0 - tl * tl, 0.0));
  float sinTV = sqrt(max(1.0 - tv * tv, 0.0));
  float k = sinTL * sinTV - tl * tv;
  float spec = k > 0.0 ? pow(k, shininess) : 0.0;
  return Ka * uAmbientLight + s * uLightColor * (Kd * sinTL + Ks * spec);
}

// Marschner, Jensen, Cammarano, Worley and Hanrahan 2003, "Light scattering from human hair
// fibers": light leaves a fibre by three paths, each a lobe around the cone of mirror directions:
// R (reflected at the surface, the light's colour times Ks), TT (transmitted through the fibre,
// tinted by the hair's colour, forward: bright where the light is behind the hair) and TRT
// (reflected inside: tinted, the secondary highlight). The real-time form of Scheuermann 2004
// ("Practical real-time hair rendering and shading": shifted tangent lobes, the secondary one
// tinted by the hair colour) with Marschner's longitudinal Gaussians and the azimuthal fits of
// Karis 2016 ("Physically based hair shading in Unreal"). Angles against the normal plane of T:
//   sin(theta_i) = T.L, sin(theta_r) = T.V, theta_h = (theta_i + theta_r) / 2,
//   theta_d = (theta_r - theta_i) / 2, phi the angle between L and V around T;
//   M_p = g(beta_p, theta_h - alpha_p), g(b, x) = exp(-x^2 / (2 b^2)) / (sqrt(2 pi) b),
//   alpha_R = -7.5 deg (the cuticle's tilt), alpha_TT = -alpha_R / 2, alpha_TRT = -3 alpha_R / 2,
//   beta_R = 7.5 deg, beta_TT = beta_R / 2, beta_TRT = 2 beta_R (Marschner's table 1);
//   N_R = cos(phi / 2) / 4, N_TT = exp(-3.65 cos(phi) - 3.98), N_TRT = exp(17 cos(phi) - 16.78);
//   S = Ks M_R N_R + Kd M_TT N_TT + Ks Kd M_TRT N_TRT, over cos^2(theta_d);
//   c = Ka La + s Ld (Kd cos(theta_i) + S cos(theta_i)),
// the Kd cos(theta_i) term standing for light scattered many times inside the coat (as
// Kajiya-Kay's diffuse: fur is light enough that it dominates).
float hairLobe(float beta, float x) {
  return exp(-0.5 * x * x / (beta * beta)) / (2.50662827 * beta);
}
// The angles of light direction L and view direction V about a hair of unit tangent T.
struct HairAngles {
  float thetaH;  // (theta_i + theta_r) / 2
  float thetaD;  // (theta_r - theta_i) / 2
  float cosD;    // cos(theta_d)
  float cosI;    // cos(theta_i)
  float cosPhi;  // cos(phi): L and V projected on T's normal plane
};
HairAngles hairAngles(vec3 T, vec3 L, vec3 V) {
  float sinI = clamp(dot(T, L), -1.0, 1.0), sinR = clamp(dot(T, V), -1.0, 1.0);
  float thetaI = asin(sinI), thetaR = asin(sinR);
  HairAngles a;
  a.thetaH = 0.5 * (thetaI + thetaR);
  a.thetaD = 0.5 * (thetaR - thetaI);
  a.cosD = cos(a.thetaD);
  a.cosI = sqrt(max(1.0 - sinI * sinI, 0.0));
  vec3 lp = L - T * sinI, vp = V - T * sinR;
  a.cosPhi = clamp(dot(lp, vp) * inversesqrt(max(dot(lp, lp) * dot(vp, vp), 1e-8)), -1.0, 1.0);
  return a;
}
// The three lobes' M_p N_p (R, TT, TRT) for a cuticle tilt alphaR and an R width betaR:
// M_p = g(beta_p, theta_h - alpha_p) with alpha_TT = -alpha_R / 2, alpha_TRT = -3 alpha_R / 2,
// beta_TT = beta_R / 2, beta_TRT = 2 beta_R; N_R = cos(phi / 2) / 4, N_TT = exp(-3.65 cos(phi) -
// 3.98), N_TRT = exp(17 cos(phi) - 16.78) (Karis 2016's azimuthal fits).
vec3 hairLobes(HairAngles a, float alphaR, float betaR) {
  float nR = 0.25 * sqrt(0.5 + 0.5 * a.cosPhi);
  float nTT = exp(-3.65 * a.cosPhi - 3.98);
  float nTRT = exp(17.0 * a.cosPhi - 16.78);
  return vec3(hairLobe(betaR, a.thetaH - alphaR) * nR,
              hairLobe(0.5 * betaR, a.thetaH + 0.5 * alphaR) * nTT,
              hairLobe(2.0 * betaR, a.thetaH + 1.5 * alphaR) * nTRT);
}
vec3 marschner(vec3 T, vec3 P, vec3 Ka, vec3 Kd, vec3 Ks, float s) {
  const float alphaR = radians(-7.5), betaR = radians(7.5);
  HairAngles a = hairAngles(T, uLightDir, normalize(uEye - P));
  vec3 m = hairLobes(a, alphaR, betaR);
  vec3 S = Ks * m.x + Kd * m.y + Ks * Kd * m.z;
  return Ka * uAmbientLight + s * uLightColor * a.cosI * (Kd + S / max(a.cosD * a.cosD, 0.04));
}

// The physically based fur model (scene::HairShading::Physical), calibrated against Blender
// Cycles' Principled Hair BSDF (Chiang, Bitterli, Tappan and Burley 2016, "A practical and
// controllable hair and fur model for production path tracing") on dense coats
// (scripts/reference/, docs/reference/; the skin's shadow map is always on with it). Two parts, as
// Karis 2016 ("Physically based hair shading in Unreal") splits a strand's light:
// - the coat: light scattered many times among the hairs leaves the coat much as from a diffuse
//   surface about the style's normal N (the skin's normal carried along the hair), of the
//   multiple-scattering albedo of a finite coat, A = c^g (1 - k_p c) (fewer bounces than
//   Chiang's infinite-volume colour mapping assumes, so paler than the colour c; and a pale coat,
//   whose light scatters deeper, loses more of it to the skin beneath), keeping a share k_a of
//   the ambient (the rest stopped by the coat and the body), less where the eye looks along the
//   hair and more where it looks across it: along the fibres it sees deeper into the coat, which
//   the coat's own fibres hide from the sky; across them, the fibres' sides in the coat's top;
//   and more saturated looking along the hairs, paler across them: the light seen along them
//   went deeper, through more fibres, each absorbing more of the colours the hair absorbs
//   (the colour's luminance Y(A) kept, its hue kept: A_v below);
//   and so for the key light, less where it runs along the hairs (it passes between the fibres
//   deep into the coat, to its self-shadowed depths and the skin) and more across them (a fibre
//   intercepts light by its projected width, cos(theta_i));
//   and less where the eye looks against the light: a coat lit from behind shows the eye its
//   fibres' unlit sides (what the fibres scatter forward is the fibre part's);
//   and the coat's light falls off more slowly than a surface's as the light's incidence grows
//   grazing, k_n max(N.L, 0)^p (p = 0.4, k_n = 0.8): a volume's top layer catches light at any
//   incidence, and light entering obliquely scatters near the top, where the eye sees it (as
//   Lommel-Seeliger's law for a scattering medium is flatter than Lambert's); Cycles' key light
//   over the coat, against pelage's with Lambert's max(N.L, 0), was 1.19-1.29 times pelage's where
//   0.2 <= N.L < 0.4 and 0.92-0.95 times above 0.8 on the views facing the light, and 1.5-2.6
//   times on the lit rims of those lit from behind;
//     coat = k_a (1 + k_v (t_0 - |T.V|)) La A_v + k_d s Ld k_n max(N.L, 0)^p l(T) b(V) A,
//     A_v = Y(A) (A / Y(A))^(1 + k_c (|T.V| - t_0)),
//     l(T) = max(1 + k_l (t_0 - |T.L|), 0),  b(V) = max(1 - k_b max(-L.V, 0), 0),
//   k_v = Light::alongFibreDarkening (0.6), k_c = Light::alongFibreSaturation (1.25),
//   k_l = Light::lightAlongFibreDarkening (2), k_b = Light::coatBacklitDarkening (0.7), t_0 = 0.35
//   (the three-quarter views' mean |T.V|, where the ambient stays k_a La A; no change for lines and
//   tubes, which carry no tangent: A_v = A, l = 1);
//   k_d = 1 where the strands are opaque (lines, tubes, strands without transparency); with
//   transparent strands, k_d = 0.138 of it stays at the hair and k_s = 0.607 more reaches the
//   coat spread sideways over 0.35 hair lengths, as light scattered many times among the hairs
//   leaves the coat away from where it entered (coat_spread.frag, Light::coatSpread); that light
//   lights the coat as a layer over the body, so its N is the skin's under the pixel (from its
//   depth, hair.frag's spreadNormal, Light::coatSpreadSkinNormal) where the light a hair keeps
//   takes the hair's own normal; and the
//   coat seen at a grazing angle, its outer layer, gets k_g La A (1 - |N.V|) more ambient, N the
//   skin's normal (oit_composite.frag, renderer.cpp's kCoatGrazingAmbient);
// - the fibre, about the strand's tangent T (absent for lines and tubes, which carry none):
//   Chiang's scattering function itself (hair_bsdf.glsl) at Cycles' defaults (roughness 0.3 both
//   ways, cuticle tilt 2 deg), lit by the key light of irradiance pi Ld (Ld = 1 lights a white
//   Lambert surface to N.L, as the references' sun of irradiance pi does), in two parts, as Zinke,
//   Yuksel, Weber and Keyser 2008 ("Dual scattering approximation for fast multiple scattering in
//   hair") split a fibre's light: what reaches it straight from the key light, scattered once
//   (f_s), and what reaches it through the fibres in front, forward-scattered on the way so that its
//   directions have spread (their global multiple scattering, f_G: the same function at
//   longitudinal roughness 0.6 and azimuthal 0.85); both through the body's shadow s_b and the
//   hairs between the fibre and the light at the fibre's opacity o_f (Light::fibreLobeOpacity,
//   0.3 a crossing; the coat's o_c = Light::fibreOpacity, 0.15: T_c = the fur's transmittance):
//     fibre = pi Ld s_b T_c^(o_f / o_c) t(N.L) (w_s f_s + w_G f_G),  w_s = 0.844, w_G = 0.735,
//   t the body's terminator where the skin lies behind the hair (smoothstep from N.L = n_0 = -0.3
//   to n_1 = 0.1, N the hair's normal: its root's skin normal carried along it, twisted as the
//   coat's normalRandomize twists it; t = 1 in the fringe, beyond the skin's outline, and without
//   the skin's depth, hair.frag): the light reaching a hair on the body's
//   unlit side crosses the coat at a grazing angle, through more fibres than the opacity map's
//   low-pass and its subsample of the hairs count (on the views lit from behind, over the unlit
//   skin, pelage's fibre part without t was 5-10 times Cycles' light scattered once there), while
//   the fringe's hairs stand out in the light.
//   (Until 2026-12-07: Marschner's lobes with Karis's azimuthal fits and without the pi, a third
//   of what Cycles' light passes show a fibre scatters once facing the light, README.)
// g, k_p, k_v, k_l, k_b, k_c were fitted on the full frames and on the light's two parts apart
// against Cycles' (scripts/reference/views.py parts, README); k_a, k_d, k_s, k_g, w_s and w_G on
// the six committed views' full frames with Chiang's fibre (2026-12-07), which leaves the coat the
// light Cycles' hairs scatter many times (views.py passes, README); p, k_n, n_0 and n_1 on those
// six views' full frames (2026-12-08; their mean MAE 9.31 -> 8.61, the held-out view's 9.01 ->
// 8.90).
const float kPhysGamma = 0.7;     // g: the coat's albedo exponent
const float kPhysPaleLoss = 0.2;  // k_p: the share of a white coat's light lost to the skin
const float kPhysAmbient = 0.722;  // k_a: the share of the ambient the coat keeps
const float kAlongFibrePivot = 0.35;  // t_0: where k_v, k_c (|T.V|), k_l (|T.L|) do nothing
// The coat's multiple-scattering albedo A = c^g (1 - k_p c).
vec3 coatAlbedo(vec3 c) {
  return pow(max(c, vec3(1e-4)), vec3(kPhysGamma)) * (1.0 - kPhysPaleLoss * c);
}
// The coat of albedo A as its ambient light shows it to the eye (V, unit, towards it) by the
// hairs' direction T: (1 + k_v (t_0 - |T.V|)) A_v above (A without a tangent).
vec3 coatAmbientSeen(vec3 A, vec3 T, vec3 V) {
  if (dot(T, T) < 0.5) return A;
  float tv = abs(dot(T, V));
  float k = max(1.0 + uAlongFibreSaturation * (tv - kAlongFibrePivot), 0.0);
  float y = max(dot(A, vec3(0.2126, 0.7152, 0.0722)), 1e-4);
  float seen = 1.0 + uAlongFibreDarkening * (kAlongFibrePivot - tv);
  return seen * y * pow(max(A / y, vec3(1e-4)), vec3(k));
}
// The share of the key light the coat catches by the hairs' direction and shows the eye (V,
// unit, towards it), l(T) b(V) above (l = 1 without a tangent).
float coatLightCaught(vec3 T, vec3 V) {
  float against = max(-dot(uLightDir, V), 0.0);
  float b = max(1.0 - uCoatBacklitDarkening * against, 0.0);
  return dot(T, T) < 0.5
             ? b
             : b * max(1.0 + uLightAlongFibreDarkening * (kAlongFibrePivot -
                                                          abs(dot(T, uLightDir))),
                       0.0);
}
// The coat's response to the key light's incidence, k_n max(N.L, 0)^p above.
const float kCoatIncidencePower = 0.4;  // p
const float kCoatIncidenceScale = 0.8;  // k_n
float coatIncidence(vec3 N) {
  return kCoatIncidenceScale * pow(max(dot(N, uLightDir), 0.0), kCoatIncidencePower);
}
// The body's terminator for the fibre part, t above, for the hair's unit normal n: 0 below
// n.L = n_0, 1 above n_1.
const float kFibreTerminatorLow = -0.3;  // n_0
const float kFibreTerminatorHigh = 0.1;  // n_1
float fibreTerminator(vec3 n) {
  return smoothstep(kFibreTerminatorLow, kFibreTerminatorHigh, dot(n, uLightDir));
}
// The fibre part's weights w_s and w_G and f_G's roughness (above).
const float kFibreOnce = 0.844;
const float kFibreSpread = 0.735;
const float kFibreSpreadRoughness = 0.6;
const float kFibreSpreadAzimuthalRoughness = 0.85;
uniform float uFibreLobeShadowPower;  // o_f / o_c (renderer.cpp; 1 without the fur's shadow)
// The physical model's colour for a hair point: coatDirect is k_d above, shadow the body's (x) and
// the fur's (y) factors of the key light (shadowFactors()), skinBehind 1 where the skin lies
// behind the hair under its pixel (the fibre part's terminator t applies), 0 elsewhere.
vec3 physicalFur(vec3 N, vec3 T, vec3 P, vec3 c, vec2 shadow, float coatDirect, float skinBehind) {
  vec3 L = uLightDir;
  vec3 V = normalize(uEye - P);
  vec3 albedo = coatAlbedo(c);
  float s = shadow.x * shadow.y;
  float direct = coatDirect * s * coatIncidence(N) * coatLightCaught(T, V);
  vec3 color = coatShown() ? kPhysAmbient * uAmbientLight * coatAmbientSeen(albedo, T, V) +
                                direct * uLightColor * albedo
                          : vec3(0.0);
  if (dot(T, T) < 0.5 || !fibreShown()) return color;
  float fibreShadow = shadow.x * pow(shadow.y, uFibreLobeShadowPower) *
                      mix(1.0, fibreTerminator(N), skinBehind);
  if (!(fibreShadow > 0.0)) return color;
  vec3 once, spread;
  hairScattering(T, L, V, hairSigmaA(c, 0.3), radians(2.0), hairRoughness(0.3, 0.3),
                 hairRoughness(kFibreSpreadRoughness, kFibreSpreadAzimuthalRoughness), once,
                 spread);
  return color +
         kHairPi * fibreShadow * uLightColor * (kFibreOnce * once + kFibreSpread * spread);
}
