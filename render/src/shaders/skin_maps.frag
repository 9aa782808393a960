// The skin's maps, one pass over the frame's pixels after the opaque pass (renderer.cpp's
// copySkinDepth), before the transparent strands: from the skin's depth as the opaque pass left it
// (uSkinDepth), the skin's depth beyond its outline and the skin's normal under each pixel.
layout(binding = 11) uniform sampler2D uSkinDepth;
uniform mat4 uInverseProjection;
uniform mat3 uEyeToWorld;  // the view's rotation inverted
uniform float uReach;      // pixels
// The skin's depth beyond its outline, for the transparent strands' weights inside the coat
// (hair.frag, Light::coatSeenDepth): where no skin lies under a pixel (the fringe), a strand's depth
// is measured from the nearest skin within uReach pixels (renderer.cpp's kFringeReach hair
// lengths), so that the weights do not step at the outline: each pixel takes the skin's depth
// under it or else the nearest of the first of six rings of eight directions about it (radii 1/12
// to 1 of the reach, 1 pixel at least) that meets the skin; 1 where none does. (At half or a
// quarter of the frame's resolution, tried, the frames' Laplacian spread against the light fell
// from 90 and 94 % of Cycles' to 84 to 88 %, at the same MAE.)
layout(location = 0) out float fDepth;
// The skin's unit normal under the pixel, turned towards the eye, in world space, and its |N.V| (V
// towards the eye): the coat's spread light (hair.frag's spreadNormal) and the resolve's grazing
// ambient (oit_composite.frag) read it; (0, 0, 0, 0) where no skin lies under the pixel.
layout(location = 1) out vec4 fNormal;
// The skin's point under pixel q in eye space.
vec3 skinPoint(ivec2 q, ivec2 size) {
  q = clamp(q, ivec2(0), size - 1);
  vec4 ndc = vec4((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0,
                  texelFetch(uSkinDepth, q, 0).r * 2.0 - 1.0, 1.0);
  vec4 v = uInverseProjection * ndc;
  return v.xyz / v.w;
}
// The normal from the depth, in eye space: the cross product of the nearer of the two one-sided differences 3
// pixels along x and along y (as screen-space ambient occlusion takes normals from depth, so that
// the outline's depth step is not one of them).
vec4 skinNormal(ivec2 p, ivec2 size) {
  const int o = 3;
  vec3 P = skinPoint(p, size);
  vec3 xp = skinPoint(p + ivec2(o, 0), size) - P, xm = P - skinPoint(p - ivec2(o, 0), size);
  vec3 yp = skinPoint(p + ivec2(0, o), size) - P, ym = P - skinPoint(p - ivec2(0, o), size);
  vec3 dx = abs(xp.z) < abs(xm.z) ? xp : xm;
  vec3 dy = abs(yp.z) < abs(ym.z) ? yp : ym;
  vec3 n = cross(dx, dy);
  if (!(dot(n, n) > 0.0)) return vec4(0.0);
  n = normalize(n);
  n = dot(n, -P) < 0.0 ? -n : n;
  return vec4(n, dot(n, normalize(-P)));
}
void main() {
  ivec2 size = textureSize(uSkinDepth, 0);
  vec2 c = gl_FragCoord.xy;
  float skin = texelFetch(uSkinDepth, ivec2(c), 0).r;
  fNormal = vec4(0.0);
  if (skin < 1.0) {
    vec4 n = skinNormal(ivec2(c), size);
    fNormal = vec4(uEyeToWorld * n.xyz, n.a);
  }
  const float rings[6] = float[6](1.0, 2.0, 4.0, 6.0, 9.0, 12.0);
  for (int k = 0; k < 6 && skin >= 1.0; ++k) {
    float r = max(uReach * rings[k] / 12.0, 1.0);
    for (int i = 0; i < 8; ++i) {
      float angle = 0.7853982 * float(i);
      ivec2 q = clamp(ivec2(c + r * vec2(cos(angle), sin(angle))), ivec2(0), size - 1);
      skin = min(skin, texelFetch(uSkinDepth, q, 0).r);
    }
  }
  fDepth = skin;
}
