// Weighted blended OIT's resolve (McGuire and Bavoil 2013): the strands' weighted mean colour over
// what lies behind them, which keeps the revealage (the product of 1 - alpha) of it; blended with
// (src alpha, 1 - src alpha) into the linear-space colour target, alpha = 1 - revealage: the
// coverage, composited over the alpha below (renderer.cpp).
// Under the physical fur model the strands' mean coat albedo A (uCoat's rgb, weighted as the
// colour) also receives the coat's spread direct light (coat_spread.frag): colour += k_s Ld A E~,
// E~ the spread irradiance at this pixel (bilinear from the low-resolution target); and an ambient
// by how the coat is seen (renderer.cpp's kCoatGrazingAmbient, k_g): colour += k_g La A (1 - |N.V|),
// N the skin's normal under the pixel from its depth (the nearer of the two one-sided differences
// 3 pixels along x and y, as screen-space ambient occlusion takes normals from depth), V towards
// the eye; where no skin lies behind (the fringe) the coat is all outer layer, |N.V| = 0.
layout(binding = 3) uniform sampler2D uAccum;
layout(binding = 4) uniform sampler2D uReveal;
layout(binding = 9) uniform sampler2D uCoat;
layout(binding = 10) uniform sampler2D uSpread;  // (E~ m, m) at 1 / uSpreadFactor resolution
uniform float uCoatSpreadShare;                  // k_s; 0: no spread light
uniform float uSpreadFactor;
uniform vec2 uSpreadSize;                        // the low-resolution target's used size
uniform vec3 uLightColor;
uniform vec3 uAmbientLight;
uniform float uCoatGrazing;  // k_g; 0: off
// The skin's normal under each pixel from its depth and its |N.V| in a (skin_maps.frag; 0 without
// skin).
layout(binding = 13) uniform sampler2D uSkinNormal;
layout(location = 0) out vec4 fColor;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float reveal = texelFetch(uReveal, p, 0).r;
  if (reveal >= 1.0) discard;
  vec4 accum = texelFetch(uAccum, p, 0);
  float w = max(accum.a, 1e-20);
  vec3 c = accum.rgb / w;
  if (uCoatSpreadShare > 0.0) {
    vec2 q = min(gl_FragCoord.xy / uSpreadFactor, uSpreadSize - 0.5);
    vec2 e = texture(uSpread, q / vec2(textureSize(uSpread, 0))).rg;
    c += uCoatSpreadShare * uLightColor * (texelFetch(uCoat, p, 0).rgb / w) * (e.x / max(e.y, 1e-12));
  }
  if (uCoatGrazing > 0.0) {
    float facing = texelFetch(uSkinNormal, p, 0).a;
    c += uCoatGrazing * uAmbientLight * (texelFetch(uCoat, p, 0).rgb / w) * (1.0 - facing);
  }
  fColor = vec4(c, 1.0 - reveal);
}
