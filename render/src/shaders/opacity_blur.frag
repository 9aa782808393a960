// The deep opacity map low-passed once per frame (deep_opacity.frag), into a half-size target:
// each texel averages four bilinear taps of the layers' first mipmap level around it (about 6x6
// texels of the map) and keeps the nearest hair depth z0 over the 4x4 map texels around it. The
// map counts hairs, and fewer, wider hairs (culled and widened) would otherwise show their grain
// in the shadow; a sparse coat would show its texels with and without a hair (z0 jumping between
// the hair and nothing) as blocks. The lighting reads both with one bilinear fetch each.
layout(binding = 5) uniform sampler2D uHairDepth;       // z0, full size
layout(binding = 7) uniform sampler2D uOpacitySource;  // the layers, with one mipmap level
layout(location = 0) out vec4 fOpacity;
layout(location = 1) out float fDepth;
void main() {
  vec2 size = vec2(textureSize(uOpacitySource, 1));
  vec2 q = gl_FragCoord.xy / size;
  vec2 h = 0.75 / size;
  fOpacity = 0.25 * (textureLod(uOpacitySource, q + vec2(-h.x, -h.y), 1.0) +
                     textureLod(uOpacitySource, q + vec2(h.x, -h.y), 1.0) +
                     textureLod(uOpacitySource, q + vec2(-h.x, h.y), 1.0) +
                     textureLod(uOpacitySource, q + vec2(h.x, h.y), 1.0));
  ivec2 base = ivec2(gl_FragCoord.xy) * 2 - 1;
  ivec2 last = textureSize(uHairDepth, 0) - 1;
  float z = 1.0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      z = min(z, texelFetch(uHairDepth, clamp(base + ivec2(x, y), ivec2(0), last), 0).r);
  fDepth = z;
}
