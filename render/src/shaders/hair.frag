#ifdef STRAND
in vec3 gPosition;
in vec3 gShading;
in vec3 gColor;
flat in vec3 gTangent;
noperspective in float gEdge;
noperspective in float gHalfWidth;
noperspective in float gCoverage;
#define P_IN gPosition
#define S_IN gShading
#define C_IN gColor
#define T_IN gTangent
#else
in vec3 vPosition;
in vec3 vShading;
in vec3 vColor;
#define P_IN vPosition
#define S_IN vShading
#define C_IN vColor
#define T_IN vec3(0.0)  // lines and tubes carry no tangent: the physical model's coat term only
#endif
uniform vec3 uKa;
uniform vec3 uKd;
uniform vec3 uKs;
uniform float uShininess;
uniform int uShading;  // scene::HairShading: 0 paper, 1 Kajiya-Kay, 2 Marschner, 3 physical
uniform bool uPerHairColor;  // the hair's colour is its diffuse, times uAmbientRatio its ambient
uniform float uAmbientRatio;
uniform float uShadowBias;
uniform float uCoatDirect;  // the physical model's k_d (lighting.glsl): 1 unless the coat spreads
#ifdef OIT
// Weighted blended order-independent transparency (McGuire and Bavoil 2013): every strand fragment
// adds its premultiplied colour times a weight to the accumulation target and multiplies the
// revealage by (1 - alpha); a full-screen pass resolves colour = sum / weight sum over the scene
// with alpha = 1 - revealage. The weight favours the near side of the creature (t = 0 at its
// nearest point, 1 at its farthest) and, inside the coat, the strands nearest the eye: a strand is
// seen through the coat in front of it, whose transmittance falls exponentially with the depth
// (Beer-Lambert), so its weight is also exp(d / lambda), d its depth in front of the skin under
// the pixel (uSkinDepth, as the opaque pass left it), lambda = uFrontDepth (Light::coatSeenDepth
// hair lengths; 0: off). The weights are a ratio, so measuring d from the skin instead of from
// the nearest strand changes nothing but their range. Where no skin lies under the pixel (the
// fringe, beyond the skin's outline) d is measured from the nearest skin within 1.5 hair lengths
// (uFringeDepth, skin_maps.frag), so that the weights do not step at the outline; farther out,
// and beyond 30 lambda, d / lambda is 30.
uniform vec2 uDepthRange;  // distance from the eye to the creature's bounds: near, far
layout(binding = 11) uniform sampler2D uSkinDepth;    // the skin's depth (the opaque pass's)
layout(binding = 12) uniform sampler2D uFringeDepth;  // the skin's depth beyond its outline
uniform float uFrontDepth;  // lambda, metres; 0: off
uniform bool uSkinBehindKnown;  // uSkinDepth is this frame's, under the physical model
uniform vec2 uDepthUnproject;  // the projection's (2, 2) and (2, 3): a depth's distance along -z
float eyeDistance(float depth) {
  return uDepthUnproject.y / (2.0 * depth - 1.0 + uDepthUnproject.x);
}
// The skin's depth under pixel p (skin, uSkinDepth's texel there), or in the fringe the nearest
// skin's (skin_maps.frag); 1 where none.
float coatBaseDepth(ivec2 p, float skin) {
  return skin < 1.0 ? skin : texelFetch(uFringeDepth, p, 0).r;
}
// The normal the physical model's spread light takes (lighting.glsl, Light::coatSpreadSkinNormal):
// the hair's own normal u turned by uSpreadSkinNormal towards the skin's under the pixel (from its
// depth, skin_maps.frag, in world space); u where no skin lies under the pixel (the fringe) or
// without the skin's depth (uSpreadSkinNormal 0).
layout(binding = 13) uniform sampler2D uSkinNormal;
uniform float uSpreadSkinNormal;
vec3 spreadNormal(vec3 u) {
  if (uSpreadSkinNormal <= 0.0) return u;
  vec3 n = texelFetch(uSkinNormal, ivec2(gl_FragCoord.xy), 0).xyz;
  if (dot(n, n) == 0.0) return u;
  vec3 m = mix(u, n, uSpreadSkinNormal);
  return dot(m, m) > 1e-12 ? normalize(m) : u;
}
layout(location = 0) out vec4 fAccum;
layout(location = 1) out float fReveal;
// Under the physical model: the coat albedo and direct irradiance E = s k_n max(N.L, 0)^p l(T) b(V)
// (lighting.glsl; N = spreadNormal(u)), weighted as the colour, that coat_spread.frag spreads
// sideways (a = 0 elsewhere).
layout(location = 2) out vec4 fCoat;
#else
layout(location = 0) out vec4 fColor;
#endif
void main() {
#ifdef OIT
  // Coverage first: the fringe beyond the strand's edge is dropped before any lighting.
  float a = clamp(gHalfWidth + 0.5 - abs(gEdge), 0.0, 1.0) * gCoverage;
  if (a < 1.0 / 1024.0) discard;
#endif
  vec3 v = S_IN;
  float len = length(v);
  vec3 u = len > 0.0 ? v / len : vec3(0.0, 0.0, 1.0);
  vec2 shadow = shadowFactors(P_IN, uShadowBias);
  float s = shadow.x * shadow.y;
  vec3 kd = uPerHairColor ? C_IN : uKd;
  vec3 ka = uPerHairColor ? C_IN * uAmbientRatio : uKa;
#ifdef OIT
  // The skin's depth under the pixel (1 where none), read once for the terminator and the weights
  // (both need this frame's, copySkinDepth).
  float skinHere = uSkinBehindKnown || uFrontDepth > 0.0
                       ? texelFetch(uSkinDepth, ivec2(gl_FragCoord.xy), 0).r
                       : 1.0;
  // Whether the skin lies behind the hair under its pixel (the physical model's fibre terminator
  // applies; lighting.glsl): not in the fringe, beyond the skin's outline.
  float skinBehind = uSkinBehindKnown && skinHere < 1.0 ? 1.0 : 0.0;
#else
  float skinBehind = 0.0;  // unknown without the skin's depth: no terminator
#endif
  vec3 c = uShading == 3   ? physicalFur(u, T_IN, P_IN, kd, shadow, uCoatDirect, skinBehind)
           : hairPassed(uShading == 2   ? marschner(u, P_IN, ka, kd, uKs, s)
                        : uShading == 1 ? kajiyaKay(u, P_IN, ka, kd, uKs, uShininess, s)
                                        : phong(u, P_IN, ka, kd, uKs, uShininess, s));
#ifdef OIT
  float t = clamp((distance(uEye, P_IN) - uDepthRange.x) / max(uDepthRange.y - uDepthRange.x, 1e-6),
                  0.0, 1.0);
  float w = a * (0.05 + 10.0 * pow(1.0 - t, 3.0));
  if (uFrontDepth > 0.0) {
    float skin = coatBaseDepth(ivec2(gl_FragCoord.xy), skinHere);
    float d = skin >= 1.0 ? 30.0
                          : clamp((eyeDistance(skin) - eyeDistance(gl_FragCoord.z)) / uFrontDepth,
                                  0.0, 30.0);
    w *= exp(d);
  }
  fAccum = vec4(c * a, a) * w;
  fReveal = a;
  fCoat = vec4(0.0);
  if (uShading == 3) {
    float e = s * coatIncidence(spreadNormal(u)) *
              coatLightCaught(T_IN, normalize(uEye - P_IN));
    fCoat = vec4(coatAlbedo(kd), e) * (a * w);
  }
#else
  fColor = vec4(c, 1.0);
#endif
}
