// The physical fur model's coat light spread sideways (renderer.cpp, Light::coatSpread): light
// scattered many times among the hairs leaves the coat away from where it entered, softening the
// body's shadow edges and filling shadowed fur from the lit fur beside it. Done as screen-space
// subsurface scattering is (Jimenez, Sundstedt and Gutierrez 2009, "Screen-space perceptual
// rendering of human skin": the diffuse irradiance blurred in screen space by a separable kernel
// whose width is a distance on the surface): the strands' mean direct irradiance per pixel,
// E = s k_n max(N.L, 0)^p l(T) b(V) (the coat term of lighting.glsl's physicalFur, N the skin's
// normal under the pixel: hair.frag's spreadNormal), weighted as the transparent strands weight
// their colour, is
// - pass 0: averaged over uFactor x uFactor pixels into (E m, m), m the share of them with strands;
// - passes 1, 2: blurred along x, then y, by a Gaussian of uSigma low-resolution pixels.
// The resolve (oit_composite.frag) reads E~ = (E m)~ / m~: the mean over the coat's pixels alone.
layout(binding = 3) uniform sampler2D uAccum;  // the strands' weighted colour sum; a: weight sum
layout(binding = 9) uniform sampler2D uCoat;   // a: the strands' weighted irradiance E sum
layout(binding = 10) uniform sampler2D uSource;  // the previous pass's (E m, m)
uniform int uPass;
uniform int uFactor;
uniform ivec2 uSize;  // the low-resolution target's used size
uniform ivec2 uDir;
uniform float uSigma;
layout(location = 0) out vec2 fOut;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 sum = vec2(0.0);
  if (uPass == 0) {
    ivec2 size = textureSize(uAccum, 0);
    for (int y = 0; y < uFactor; ++y)
      for (int x = 0; x < uFactor; ++x) {
        ivec2 q = p * uFactor + ivec2(x, y);
        if (any(greaterThanEqual(q, size))) continue;
        float w = texelFetch(uAccum, q, 0).a;
        if (w > 0.0) sum += vec2(texelFetch(uCoat, q, 0).a / w, 1.0);
      }
    fOut = sum / float(uFactor * uFactor);
    return;
  }
  int r = int(ceil(3.0 * uSigma));
  for (int i = -r; i <= r; ++i) {
    ivec2 q = p + uDir * i;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, uSize))) continue;
    float x = float(i) / uSigma;
    sum += exp(-0.5 * x * x) * texelFetch(uSource, q, 0).rg;
  }
  fOut = sum;
}
