// Weighted blended OIT's resolve (McGuire and Bavoil 2013): the strands' weighted mean colour over
// what lies behind them, which keeps the revealage (the product of 1 - alpha) of it; blended with
// (src alpha, 1 - src alpha) into the linear-space colour target, alpha = 1 - revealage: the
// coverage, composited over the alpha below (renderer.cpp).
layout(binding = 3) uniform sampler2D uAccum;
layout(binding = 4) uniform sampler2D uReveal;
layout(location = 0) out vec4 fColor;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float reveal = texelFetch(uReveal, p, 0).r;
  if (reveal >= 1.0) discard;
  vec4 accum = texelFetch(uAccum, p, 0);
  fColor = vec4(accum.rgb / max(accum.a, 1e-20), 1.0 - reveal);
}
