// Hair points seen from the light for the deep opacity map (deep_opacity.frag): the position and
// where the point lies along its hair (0 at the root, 1 at the tip; as hair.vert), and the hair's
// width scale (hair.vert's).
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProj;
uniform int uPointsPerStrand;  // points along one hair (K for tubes: rings)
uniform int uStrandStride;     // 1, or M (ring size) for tubes
uniform bool uPerHairWidth;
layout(binding = 1) uniform usamplerBuffer uHairColors;  // per slot: (root, tip)
out float vAlong;
out float vWidthScale;
void main() {
  int k = (gl_VertexID % (uPointsPerStrand * uStrandStride)) / uStrandStride;
  vAlong = uPointsPerStrand > 1 ? float(k) / float(uPointsPerStrand - 1) : 0.0;
  vWidthScale = uPerHairWidth
                    ? hairWidthScale(texelFetch(uHairColors, gl_VertexID / (uPointsPerStrand * uStrandStride)).xy)
                    : 1.0;
  gl_Position = uViewProj * vec4(aPosition, 1.0);
}
