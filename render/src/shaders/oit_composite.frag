// Weighted blended OIT's resolve (McGuire and Bavoil 2013): the strands' weighted mean colour over
// what lies behind them, which keeps the revealage (the product of 1 - alpha) of it; blended with
// (src alpha, 1 - src alpha) into the linear-space colour target, alpha = 1 - revealage: the
// coverage, composited over the alpha below (renderer.cpp).
// Under the physical fur model the strands' mean coat albedo A (uCoat's rgb, weighted as the
// colour) also receives the coat's spread direct light (coat_spread.frag): colour += k_s Ld A E~,
// E~ the spread irradiance at this pixel (bilinear from the low-resolution target).
layout(binding = 3) uniform sampler2D uAccum;
layout(binding = 4) uniform sampler2D uReveal;
layout(binding = 9) uniform sampler2D uCoat;
layout(binding = 10) uniform sampler2D uSpread;  // (E~ m, m) at 1 / uSpreadFactor resolution
uniform float uCoatSpreadShare;                  // k_s; 0: no spread light
uniform float uSpreadFactor;
uniform vec2 uSpreadSize;                        // the low-resolution target's used size
uniform vec3 uLightColor;
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
  fColor = vec4(c, 1.0 - reveal);
}
