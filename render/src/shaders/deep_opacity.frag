// Deep opacity maps (Yuksel and Keyser 2008, "Deep Opacity Maps"), the opacity pass: every hair
// fragment seen from the light adds its opacity to the layers that lie beyond it. The first pass
// drew the hairs' depth alone (z0, the nearest hair per texel); layer k holds the opacity of the
// hairs between z0 and z0 + uLayers[k] (metres along the light), so it grows with k. A hair's
// opacity in a texel is the share of the texel its width covers, min(w c / texel, 1): the map
// counts coverage, not fragments, and keeps its meaning at any map size or hair count (w the
// hair's width at the point, c the culling factor by which drawn hairs are widened). The map may
// draw a uniform subsample of the hairs, each standing for uStandsFor of them. A hair stops the
// share uFibreOpacity of the light it intercepts (scene::Light::fibreOpacity; the rest scatters on,
// forward, into the coat), as the hair opacity of opacity shadow maps (Kim and Neumann 2001).
in float vAlong;
in float vWidthScale;
uniform vec4 uLayers;        // layer ends beyond z0, metres, increasing
uniform float uDepthScale;   // metres per unit of window depth along the light
uniform float uRootWidth;    // metres
uniform float uTipWidth;
uniform float uWiden;        // c >= 1
uniform float uTexelMeters;  // the map's texel size
uniform float uStandsFor;    // hairs each drawn hair stands for (>= 1)
uniform float uFibreOpacity;  // [0, 1]
layout(binding = 5) uniform sampler2D uHairDepth;
layout(location = 0) out vec4 fOpacity;
void main() {
  float z0 = texelFetch(uHairDepth, ivec2(gl_FragCoord.xy), 0).r;
  float dz = max(gl_FragCoord.z - z0, 0.0) * uDepthScale;
  float w = mix(uRootWidth, uTipWidth, vAlong) * uWiden * vWidthScale;
  float a = min(w / uTexelMeters, 1.0) * uStandsFor * uFibreOpacity;
  fOpacity = a * vec4(lessThanEqual(vec4(dz), uLayers));
}
