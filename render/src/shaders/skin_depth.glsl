// The skin's depth as the opaque pass left it (renderer.cpp's copySkinDepth, before the
// transparent strands), and the skin's normal taken from it: the resolve's grazing ambient
// (oit_composite.frag) and the coat's spread light (hair.frag) read them.
layout(binding = 11) uniform sampler2D uSkinDepth;
uniform mat4 uInverseProjection;
// The skin's point under pixel q in eye space.
vec3 skinPoint(ivec2 q, ivec2 size) {
  q = clamp(q, ivec2(0), size - 1);
  vec4 ndc = vec4((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0,
                  texelFetch(uSkinDepth, q, 0).r * 2.0 - 1.0, 1.0);
  vec4 v = uInverseProjection * ndc;
  return v.xyz / v.w;
}
// The skin's unit normal under pixel p in eye space, turned towards the eye: the cross product of
// the nearer of the two one-sided differences 3 pixels along x and along y (as screen-space
// ambient occlusion takes normals from depth, so that the outline's depth step is not one of
// them). vec3(0) where no skin lies under p.
vec3 skinNormal(ivec2 p) {
  ivec2 size = textureSize(uSkinDepth, 0);
  if (texelFetch(uSkinDepth, p, 0).r >= 1.0) return vec3(0.0);
  const int o = 3;
  vec3 P = skinPoint(p, size);
  vec3 xp = skinPoint(p + ivec2(o, 0), size) - P, xm = P - skinPoint(p - ivec2(o, 0), size);
  vec3 yp = skinPoint(p + ivec2(0, o), size) - P, ym = P - skinPoint(p - ivec2(0, o), size);
  vec3 dx = abs(xp.z) < abs(xm.z) ? xp : xm;
  vec3 dy = abs(yp.z) < abs(ym.z) ? yp : ym;
  vec3 n = cross(dx, dy);
  if (!(dot(n, n) > 0.0)) return vec3(0.0);
  n = normalize(n);
  return dot(n, -P) < 0.0 ? -n : n;
}
